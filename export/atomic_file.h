// SPDX-License-Identifier: MIT
// Whole-or-nothing file writes: write beside the target under a temporary name, then rename.
#pragma once

#include <filesystem>
#include <string_view>

namespace inkline::output {

// Writes `contents` to `path`, creating missing parent folders. An interrupted or failed write
// leaves the previous file (if any) untouched and no temporary behind. Throws OutputError.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// The temporary name used while writing `path` (same folder, hidden, marked with the pid).
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

}  // namespace inkline::output
