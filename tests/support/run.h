// SPDX-License-Identifier: MIT
// Runs shell commands, and the inkline program when its path is compiled in as INKLINE_EXE,
// capturing their output.
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace inkline::test {

// Whether this build runs under AddressSanitizer, which reserves terabytes of address space for
// its shadow memory: address-space limits (ulimit -v, RLIMIT_AS) cannot be tested under it.
// GCC says so with __SANITIZE_ADDRESS__, clang with __has_feature(address_sanitizer).
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INKLINE_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(INKLINE_TEST_ASAN)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif

struct RunResult {
    int code = -1;       // exit status, -1 when killed by a signal
    std::string output;  // stdout and stderr together
};


// Runs a shell command line, capturing stdout and stderr.
inline RunResult run_shell(const std::string& command_line) {
    RunResult r;
    FILE* pipe = ::popen(("(" + command_line + ") 2>&1").c_str(), "r");
    std::array<char, 4096> buf{};
    while (size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
    const int status = ::pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

#ifdef INKLINE_EXE
inline std::string inkline_command() { return INKLINE_EXE; }
inline RunResult run_inkline(const std::string& args) { return run_shell(inkline_command() + " " + args); }
#endif

}  // namespace inkline::test
