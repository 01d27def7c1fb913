// SPDX-License-Identifier: MIT
#include "export/atomic_file.h"

#include "core/error.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <unistd.h>

namespace inkline::output {
namespace {

// The temporary being written, for the signal handler. A signal handler can reach nothing but
// globals; writes happen one at a time, so one slot suffices.
char g_temporary[4096];
volatile std::sig_atomic_t g_writing = 0;

extern "C" void remove_temporary_and_exit(int signal_number) {
    if (g_writing) ::unlink(g_temporary);
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

// Marks `temp` as in progress for the handler; cleared when the write ends either way.
class TemporaryGuard {
  public:
    explicit TemporaryGuard(const std::filesystem::path& temp) {
        const std::string& s = temp.native();
        if (s.size() < sizeof g_temporary) {
            std::memcpy(g_temporary, s.c_str(), s.size() + 1);
            g_writing = 1;
        }
    }
    ~TemporaryGuard() { g_writing = 0; }
    TemporaryGuard(const TemporaryGuard&) = delete;
    TemporaryGuard& operator=(const TemporaryGuard&) = delete;
};

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int error) {
    throw OutputError(path.string() + ": " + what + ": " + std::strerror(error));
}

}  // namespace

void install_interrupt_cleanup() {
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal_number, remove_temporary_and_exit);
    std::signal(SIGXFSZ, SIG_IGN);
}

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
    const TemporaryGuard guard(temp);
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
