// SPDX-License-Identifier: MIT
// Replays every file of the fuzz corpora (seeds and crashes the fuzzers found) through the fuzz
// targets, so each stays a regression test in the normal and sanitizer builds.
#include "tests/fuzz/targets.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

namespace inkline {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> bytes_of(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

size_t replay(const char* corpus, void (*target)(const uint8_t*, size_t)) {
    size_t n = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(INKLINE_FUZZ_CORPUS) / corpus)) {
        const std::vector<uint8_t> data = bytes_of(entry.path());
        SCOPED_TRACE(entry.path().filename().string());
        EXPECT_NO_THROW(target(data.data(), data.size()));
        ++n;
    }
    return n;
}

TEST(FuzzCorpus, SceneInputsParseOrFailCleanly) { EXPECT_GT(replay("scene", inkline::fuzz::scene_target), 5u); }

TEST(FuzzCorpus, MeshInputsLoadOrFailCleanly) { EXPECT_GT(replay("mesh", inkline::fuzz::mesh_target), 5u); }

void obj_target(const uint8_t* data, size_t size) { inkline::fuzz::mesh_format_target(".obj", data, size); }
void off_target(const uint8_t* data, size_t size) { inkline::fuzz::mesh_format_target(".off", data, size); }
void ply_target(const uint8_t* data, size_t size) { inkline::fuzz::mesh_format_target(".ply", data, size); }
void stl_target(const uint8_t* data, size_t size) { inkline::fuzz::mesh_format_target(".stl", data, size); }

TEST(FuzzCorpus, GltfInputsLoadOrFailCleanly) { EXPECT_GT(replay("gltf", inkline::fuzz::gltf_target), 5u); }

TEST(FuzzCorpus, MeshArraysBuildOrFailCleanly) { EXPECT_GT(replay("mesh_arrays", inkline::fuzz::mesh_arrays_target), 5u); }

TEST(FuzzCorpus, ObjInputsLoadOrFailCleanly) { EXPECT_GT(replay("obj", obj_target), 5u); }
TEST(FuzzCorpus, OffInputsLoadOrFailCleanly) { EXPECT_GT(replay("off", off_target), 5u); }
TEST(FuzzCorpus, PlyInputsLoadOrFailCleanly) { EXPECT_GT(replay("ply", ply_target), 5u); }
TEST(FuzzCorpus, StlInputsLoadOrFailCleanly) { EXPECT_GT(replay("stl", stl_target), 5u); }

}  // namespace
}  // namespace inkline
