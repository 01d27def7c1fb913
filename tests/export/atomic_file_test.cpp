// SPDX-License-Identifier: MIT
#include "export/atomic_file.h"

#include "core/error.h"
#include "tests/support/obj.h"

#include <gtest/gtest.h>

#include <unistd.h>

namespace inkline {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, WritesCreatesFoldersAndLeavesNoTemporary) {
    const fs::path dir = test::fresh_temp_dir("atomic_write");
    const fs::path target = dir / "a" / "b" / "frame.svg";
    output::write_file_atomically(target, "first");
    output::write_file_atomically(target, "second");
    EXPECT_EQ(test::read_text(target), "second");
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(target.parent_path())) {
        (void)e;
        ++entries;
    }
    EXPECT_EQ(entries, 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, UnwritableFolderIsAnOutputErrorAndKeepsTheOldFile) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
    const fs::path dir = test::fresh_temp_dir("atomic_readonly");
    output::write_file_atomically(dir / "frame.svg", "old");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(output::write_file_atomically(dir / "frame.svg", "new"), OutputError);
    fs::permissions(dir, fs::perms::owner_all);
    EXPECT_EQ(test::read_text(dir / "frame.svg"), "old");
    fs::remove_all(dir);
}

TEST(AtomicFile, PathThroughAFileIsAnOutputError) {
    const fs::path dir = test::fresh_temp_dir("atomic_notdir");
    test::write_text(dir / "file", "x");
    EXPECT_THROW(output::write_file_atomically(dir / "file" / "frame.svg", "new"), OutputError);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace inkline
