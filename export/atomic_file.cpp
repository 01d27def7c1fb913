// SPDX-License-Identifier: MIT
#include "export/atomic_file.h"

#include "core/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <unistd.h>

namespace inkline::output {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int error) {
    throw OutputError(path.string() + ": " + what + ": " + std::strerror(error));
}

}  // namespace

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
    return path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()));
}

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
    if (!path.parent_path().empty()) {
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) fail(path.parent_path(), "cannot create folder", ec.value());
    }
    const std::filesystem::path temp = temporary_path_for(path);
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail(path, "cannot write", errno);

    const char* data = contents.data();
    size_t left = contents.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, data, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int error = n < 0 ? errno : ENOSPC;
            ::close(fd);
            ::unlink(temp.c_str());
            fail(path, "cannot write", error);
        }
        data += n;
        left -= size_t(n);
    }
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        fail(path, "cannot write", error);
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        fail(path, "cannot rename into place", error);
    }
}

}  // namespace inkline::output
