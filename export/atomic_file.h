// SPDX-License-Identifier: MIT
// Whole-or-nothing file writes: write beside the target under a temporary name, then rename.
#pragma once

#include <filesystem>
#include <string_view>

namespace inkline::output {

// Writes `contents` to `path`, creating missing parent folders. An interrupted or failed write
// leaves the previous file (if any) untouched and no temporary behind. Throws OutputError.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Makes an interrupted run leave only whole files: on SIGINT, SIGTERM or SIGHUP the temporary
// being written is removed before the process ends with the signal's usual status. Also ignores
// SIGXFSZ, so a file-size limit surfaces as an OutputError instead of killing the process.
// Call once, from main().
void install_interrupt_cleanup();

// The temporary name used while writing `path` (same folder, hidden, marked with the pid).
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

}  // namespace inkline::output
