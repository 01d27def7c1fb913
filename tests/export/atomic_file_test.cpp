// SPDX-License-Identifier: MIT
#include "export/atomic_file.h"

#include "core/error.h"
#include "tests/support/obj.h"

#include <gtest/gtest.h>

#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
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

// The pid of a process that has ended (a child that exited and was waited for).
pid_t dead_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

mode_t mode_of(const fs::path& path) {
    struct stat info {};
    EXPECT_EQ(::lstat(path.c_str(), &info), 0) << path;
    return info.st_mode;
}

ino_t inode_of(const fs::path& path) {
    struct stat info {};
    EXPECT_EQ(::lstat(path.c_str(), &info), 0) << path;
    return info.st_ino;
}

size_t entries_in(const fs::path& folder) {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(folder)) n += e.exists() || e.is_symlink();
    return n;
}

TEST(AtomicFile, TemporaryNamesAreUnpredictableHiddenAndWithinNameMax) {
    const fs::path target = fs::path("out") / (std::string(250, 'n') + ".svg");
    const fs::path a = output::temporary_path_for(target), b = output::temporary_path_for(target);
    EXPECT_NE(a, b);
    EXPECT_EQ(a.parent_path(), target.parent_path());
    EXPECT_EQ(a.filename().string()[0], '.');
    EXPECT_LE(a.filename().string().size(), 255u);
    const fs::path short_name = output::temporary_path_for("frame.svg", "ABCDEFGH");
    EXPECT_EQ(short_name.string(), ".frame.svg.tmp-" + std::to_string(::getpid()) + "-ABCDEFGH");
}

TEST(AtomicFile, OutputNameOf250BytesIsWritten) {
    const fs::path dir = test::fresh_temp_dir("atomic_long_name");
    const fs::path target = dir / (std::string(246, 'n') + ".svg");
    output::write_file_atomically(target, "whole");
    EXPECT_EQ(test::read_text(target), "whole");
    EXPECT_EQ(entries_in(dir), 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, LinkPlantedAtTheOldPredictableTemporaryNameIsNotFollowed) {
    const fs::path dir = test::fresh_temp_dir("atomic_planted");
    test::write_text(dir / "victim.txt", "precious");
    const fs::path planted = dir / (".frame.svg.tmp" + std::to_string(::getpid()));
    fs::create_symlink(dir / "victim.txt", planted);
    output::write_file_atomically(dir / "frame.svg", "drawing");
    EXPECT_EQ(test::read_text(dir / "frame.svg"), "drawing");
    EXPECT_EQ(test::read_text(dir / "victim.txt"), "precious");
    EXPECT_TRUE(fs::is_symlink(planted));
    EXPECT_EQ(entries_in(dir), 3u);
    fs::remove_all(dir);
}

TEST(AtomicFile, LeftoversOfADeadRunOfTheSameOutputAreRemovedAndNothingElse) {
    const fs::path dir = test::fresh_temp_dir("atomic_leftovers");
    const std::string dead = std::to_string(dead_pid());
    test::write_text(dir / "victim.txt", "precious");
    test::write_text(dir / (".frame.svg.tmp-" + dead + "-Leftover"), "half");
    fs::create_symlink(dir / "victim.txt", dir / (".frame.svg.tmp-" + dead + "-LinkLeft"));
    // Kept: a live process's temporary, another output's, and names off the pattern.
    const std::vector<std::string> kept = {".frame.svg.tmp-1-LiveRun1", ".other.svg.tmp-" + dead + "-Leftover",
                                           ".frame.svg.tmp-" + dead + "-TooLong12", ".frame.svg.tmp-" + dead,
                                           "frame.svg.tmp-" + dead + "-Leftover", ".frame.svg.tmp-x" + dead + "-Leftover"};
    for (const std::string& name : kept) test::write_text(dir / name, "keep");
    output::write_file_atomically(dir / "frame.svg", "drawing");
    EXPECT_FALSE(fs::exists(fs::symlink_status(dir / (".frame.svg.tmp-" + dead + "-Leftover"))));
    EXPECT_FALSE(fs::exists(fs::symlink_status(dir / (".frame.svg.tmp-" + dead + "-LinkLeft"))));
    for (const std::string& name : kept) EXPECT_EQ(test::read_text(dir / name), "keep") << name;
    EXPECT_EQ(test::read_text(dir / "victim.txt"), "precious");
    EXPECT_EQ(test::read_text(dir / "frame.svg"), "drawing");
    EXPECT_EQ(entries_in(dir), kept.size() + 2);
    fs::remove_all(dir);
}

TEST(AtomicFile, NewFileHonoursTheUmaskAndAReplacedOneKeepsItsMode) {
    const fs::path dir = test::fresh_temp_dir("atomic_modes");
    const mode_t previous = ::umask(027);
    output::write_file_atomically(dir / "new.svg", "a");
    ::umask(previous);
    EXPECT_EQ(mode_of(dir / "new.svg") & 0777, 0640u);
    test::write_text(dir / "private.svg", "old");
    fs::permissions(dir / "private.svg", fs::perms::owner_read | fs::perms::owner_write);
    output::write_file_atomically(dir / "private.svg", "new");
    EXPECT_EQ(mode_of(dir / "private.svg") & 0777, 0600u);
    EXPECT_EQ(test::read_text(dir / "private.svg"), "new");
    fs::remove_all(dir);
}

TEST(AtomicFile, ReadOnlyFileIsRefusedAndKeptAlsoForRoot) {
    const fs::path dir = test::fresh_temp_dir("atomic_read_only");
    test::write_text(dir / "frame.svg", "old");
    fs::permissions(dir / "frame.svg", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    const ino_t inode = inode_of(dir / "frame.svg");
    try {
        output::write_file_atomically(dir / "frame.svg", "new");
        ADD_FAILURE() << "no OutputError";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("frame.svg: is read-only; not replaced"), std::string::npos) << e.what();
    }
    EXPECT_EQ(inode_of(dir / "frame.svg"), inode);
    EXPECT_EQ(test::read_text(dir / "frame.svg"), "old");
    EXPECT_EQ(entries_in(dir), 1u);
    fs::permissions(dir / "frame.svg", fs::perms::owner_write, fs::perm_options::add);
    fs::remove_all(dir);
}

TEST(AtomicFile, CharacterDeviceIsWrittenInPlace) {
    struct stat before {};
    ASSERT_EQ(::stat("/dev/null", &before), 0);
    output::write_file_atomically("/dev/null", "discarded");
    struct stat after {};
    ASSERT_EQ(::stat("/dev/null", &after), 0);
    EXPECT_TRUE(S_ISCHR(after.st_mode));
    EXPECT_EQ(after.st_ino, before.st_ino);
    EXPECT_EQ(after.st_rdev, before.st_rdev);
}

TEST(AtomicFile, NamedDescriptorIsWrittenAsItIsAppendingWhereItAppends) {
    const fs::path dir = test::fresh_temp_dir("atomic_descriptor");
    test::write_text(dir / "log.txt", "earlier\n");
    const ino_t inode = inode_of(dir / "log.txt");
    const int fd = ::open((dir / "log.txt").c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    ASSERT_GE(fd, 0);
    output::write_file_atomically("/dev/fd/" + std::to_string(fd), "one\n");
    output::write_file_atomically("/proc/self/fd/" + std::to_string(fd), "two\n");
    ::close(fd);
    EXPECT_EQ(test::read_text(dir / "log.txt"), "earlier\none\ntwo\n");
    EXPECT_EQ(inode_of(dir / "log.txt"), inode);
    EXPECT_EQ(entries_in(dir), 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, FifoIsWrittenInPlaceForItsReader) {
    const fs::path dir = test::fresh_temp_dir("atomic_fifo");
    ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0644), 0);
    std::string received;
    std::thread reader([&] { received = test::read_text(dir / "pipe"); });
    output::write_file_atomically(dir / "pipe", "through the pipe");
    reader.join();
    EXPECT_EQ(received, "through the pipe");
    EXPECT_TRUE(S_ISFIFO(mode_of(dir / "pipe")));
    EXPECT_EQ(entries_in(dir), 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, LinkIsFollowedAndItsFileReplacedBesideIt) {
    const fs::path dir = test::fresh_temp_dir("atomic_link");
    test::write_text(dir / "real" / "frame.svg", "old");
    fs::create_directories(dir / "links");
    fs::create_symlink(fs::path("..") / "real" / "frame.svg", dir / "links" / "frame.svg");
    output::write_file_atomically(dir / "links" / "frame.svg", "new");
    EXPECT_TRUE(fs::is_symlink(dir / "links" / "frame.svg"));
    EXPECT_EQ(fs::read_symlink(dir / "links" / "frame.svg"), fs::path("..") / "real" / "frame.svg");
    EXPECT_EQ(test::read_text(dir / "real" / "frame.svg"), "new");
    EXPECT_EQ(entries_in(dir / "links"), 1u);
    EXPECT_EQ(entries_in(dir / "real"), 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, DanglingLinkAndFolderAreRefused) {
    const fs::path dir = test::fresh_temp_dir("atomic_refused");
    fs::create_symlink(dir / "missing.svg", dir / "dangling.svg");
    EXPECT_THROW(output::write_file_atomically(dir / "dangling.svg", "x"), OutputError);
    EXPECT_FALSE(fs::exists(dir / "missing.svg"));
    fs::create_directories(dir / "folder.svg");
    EXPECT_THROW(output::write_file_atomically(dir / "folder.svg", "x"), OutputError);
    EXPECT_TRUE(fs::is_directory(dir / "folder.svg"));
    EXPECT_EQ(entries_in(dir), 2u);
    fs::remove_all(dir);
}

TEST(AtomicFile, FileIdentityIsTheSameThroughALink) {
    const fs::path dir = test::fresh_temp_dir("atomic_identity");
    test::write_text(dir / "a.obj", "v 0 0 0\n");
    fs::create_symlink(dir / "a.obj", dir / "b.obj");
    test::write_text(dir / "c.obj", "v 0 0 0\n");
    EXPECT_EQ(output::file_identity(dir / "a.obj"), output::file_identity(dir / "b.obj"));
    EXPECT_NE(output::file_identity(dir / "a.obj"), output::file_identity(dir / "c.obj"));
    EXPECT_FALSE(output::file_identity(dir / "missing.obj").has_value());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace inkline
