// SPDX-License-Identifier: MIT
// Test helpers: write meshes and text files into a per-test temporary folder.
#pragma once

#include "core/mesh/mesh.h"

#include <filesystem>
#include <string>

namespace inkline::test {

void write_obj(const std::filesystem::path& path, const core::Mesh& mesh);
void write_text(const std::filesystem::path& path, const std::string& text);
std::string read_text(const std::filesystem::path& path);

// A fresh, empty folder under the system temporary folder, unique to the named test.
std::filesystem::path fresh_temp_dir(const std::string& name);

}  // namespace inkline::test
