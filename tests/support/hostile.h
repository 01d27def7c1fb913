// SPDX-License-Identifier: MIT
// Helpers for the hostile suites (tests/cli/hostile_*_test.cpp): the state of every file in a
// folder before and after a run, and the shape of an error report.
#pragma once

#include "tests/support/obj.h"
#include "tests/support/run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include <sys/stat.h>

namespace inkline::test {

// One entry of a folder, as lstat sees it (links are not followed).
struct FileState {
    mode_t mode = 0;        // type and permission bits
    off_t size = 0;
    ino_t inode = 0;        // a replaced file gets a new inode
    size_t content = 0;     // hash of a regular file's bytes, or of a link's target
    bool operator==(const FileState&) const = default;
};

// Every entry under `root` (recursively, relative paths), links not followed.
inline std::map<std::string, FileState> folder_state(const std::filesystem::path& root) {
    namespace fs = std::filesystem;
    std::map<std::string, FileState> state;
    if (!fs::exists(fs::symlink_status(root))) return state;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        struct stat info {};
        if (::lstat(it->path().c_str(), &info) != 0) continue;
        FileState s{info.st_mode, info.st_size, info.st_ino, 0};
        if (S_ISREG(info.st_mode)) {
            std::error_code ec;
            const auto perms = fs::status(it->path(), ec).permissions();
            if ((perms & fs::perms::owner_read) != fs::perms::none) {
                FILE* f = std::fopen(it->path().c_str(), "rb");
                if (f) {
                    std::string bytes;
                    char buf[65536];
                    while (size_t n = std::fread(buf, 1, sizeof buf, f)) bytes.append(buf, n);
                    std::fclose(f);
                    s.content = std::hash<std::string>{}(bytes);
                }
            }
        } else if (S_ISLNK(info.st_mode)) {
            s.content = std::hash<std::string>{}(fs::read_symlink(it->path()).string());
        }
        state[it->path().lexically_relative(root).string()] = s;  // fs::relative would follow links
    }
    return state;
}

// The names in `after` that are not in `before` or differ from it.
inline std::vector<std::string> changed_entries(const std::map<std::string, FileState>& before,
                                                const std::map<std::string, FileState>& after) {
    std::vector<std::string> changed;
    for (const auto& [name, state] : after) {
        const auto it = before.find(name);
        if (it == before.end() || !(it->second == state)) changed.push_back(name);
    }
    for (const auto& [name, state] : before) {
        if (!after.count(name)) changed.push_back(name + " (removed)");
    }
    return changed;
}

// Asserts that a run failed with `code` and reported exactly one short line:
// "inkline: error: ..." containing `needle`.
inline void expect_one_line_error(const RunResult& r, int code, const std::string& needle) {
    EXPECT_EQ(r.code, code) << r.output;
    EXPECT_EQ(r.output.rfind("inkline: error: ", 0), 0u) << r.output;
    const size_t newline = r.output.find('\n');
    EXPECT_EQ(newline, r.output.size() - 1) << "more than one line:\n" << r.output;
    EXPECT_LE(r.output.size(), 400u) << "error line too long:\n" << r.output.substr(0, 600);
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in:\n" << r.output;
}

// A fixture with a fresh folder per test, removed afterwards (read-only entries made writable).
class HostileTest : public ::testing::Test {
  protected:
    std::filesystem::path dir =
        fresh_temp_dir(std::string("hostile_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override {
        std::error_code ec;
        for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
             it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
            if (!it->is_symlink()) std::filesystem::permissions(it->path(), std::filesystem::perms::owner_all,
                                                                std::filesystem::perm_options::add, ec);
        }
        std::filesystem::remove_all(dir, ec);
    }
};

}  // namespace inkline::test
