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

}  // namespace
}  // namespace inkline
