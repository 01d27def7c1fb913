// SPDX-License-Identifier: MIT
// Whole-or-nothing file writes: write beside the target under a temporary name, then rename.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace inkline::output {

// Writes `contents` to `path`, creating missing parent folders. Throws OutputError.
// - A new or regular file is written under a temporary name beside it and renamed into place:
//   an interrupted or failed write leaves the previous file (if any) untouched and no temporary
//   behind. A replaced file keeps its permission bits; a new one gets 0666 less the umask.
// - An existing file without write permission (for root: without any write bit) is refused and
//   left as it is.
// - A character device or FIFO (/dev/null, a named pipe) is written in place: opened for
//   writing, never created, truncated or replaced. Block devices, sockets and folders are refused.
// - A symbolic link is followed: the link stays, and the file it leads to is written as above
//   (a regular file is replaced in its own folder). A link that leads nowhere is refused.
// - /dev/stdout, /dev/stderr, /dev/fd/N and /proc/self/fd/N write to that open descriptor as it
//   is (a pipe, or a file the shell opened, appending or not).
// Temporaries are created exclusively under unpredictable names (O_EXCL, O_NOFOLLOW); leftovers
// of killed runs writing the same output (their process no longer running) are removed first.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Makes an interrupted run leave only whole files: on SIGINT, SIGTERM or SIGHUP the temporary
// being written is removed before the process ends with the signal's usual status. Also ignores
// SIGXFSZ and SIGPIPE, so a file-size limit or a FIFO whose reader went away surfaces as an
// OutputError instead of killing the process. Call once, from main().
void install_interrupt_cleanup();

// The name of a temporary for writing `path`: in the same folder, hidden, marked with the pid and
// `unique` (random letters and digits), within NAME_MAX however long the output's name is:
// ".NAME.tmp-PID-UNIQUE", NAME cut to its first 100 bytes plus "~" and a hash of the whole name
// when it is longer. With no `unique`, a fresh random one (for a program that writes the file
// itself; write_file_atomically creates its temporaries exclusively).
std::filesystem::path temporary_path_for(const std::filesystem::path& path, std::string_view unique = {});

// A file's identity (device and inode, links followed), or none when it does not exist: two
// paths with the same identity name the same file.
struct FileIdentity {
    dev_t device = 0;
    ino_t inode = 0;
    bool operator==(const FileIdentity&) const = default;
};
std::optional<FileIdentity> file_identity(const std::filesystem::path& path);

}  // namespace inkline::output
