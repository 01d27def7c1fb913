// SPDX-License-Identifier: MIT
#include "export/atomic_file.h"

#include "core/error.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <dirent.h>
#include <signal.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace inkline::output {
namespace {

namespace fs = std::filesystem;

// An output name longer than this is cut in its temporary's name (NAME_MAX is 255 bytes).
constexpr size_t kMaxEmbeddedName = 100;
constexpr size_t kUniqueLength = 8;
constexpr std::string_view kUniqueAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";

// Temporaries being written, for the signal handler, which can reach nothing but globals: a
// slot per temporary, so that several threads may write files at once. A thread holds its slot
// kCreating while it creates the file (the handler waits for that to end) and kHeld while the
// file may exist (the handler removes it).
enum SlotState : int { kFree = 0, kCreating = 1, kHeld = 2 };
struct TemporarySlot {
    std::atomic<int> state{kFree};
    char path[4096];
};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);
constexpr size_t kTemporarySlots = 8;
TemporarySlot g_temporaries[kTemporarySlots];
// Set by the handler before it looks at the slots: no temporary is created after it.
std::atomic<bool> g_stopping{false};

extern "C" void remove_temporary_and_exit(int signal_number) {
    g_stopping.store(true);
    for (TemporarySlot& slot : g_temporaries) {
        int state = slot.state.load();
        while (state == kCreating) state = slot.state.load();
        if (state == kHeld) ::unlink(slot.path);
    }
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

[[noreturn]] void fail(const fs::path& path, const std::string& what, int error) {
    throw OutputError(path.string() + ": " + what + ": " + std::strerror(error));
}

[[noreturn]] void refuse(const fs::path& path, const std::string& why) { throw OutputError(path.string() + ": " + why); }

// Blocks SIGINT, SIGTERM and SIGHUP while a temporary is created and registered, so the handler
// never misses one that exists nor removes one that is not ours.
class InterruptsBlocked {
  public:
    InterruptsBlocked() {
        sigset_t set;
        sigemptyset(&set);
        for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, s);
        pthread_sigmask(SIG_BLOCK, &set, &previous_);
    }
    ~InterruptsBlocked() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
    InterruptsBlocked(const InterruptsBlocked&) = delete;
    InterruptsBlocked& operator=(const InterruptsBlocked&) = delete;

  private:
    sigset_t previous_;
};

// A slot of g_temporaries held kCreating for `path`, or null when the path does not fit one.
// Waits while every slot is taken (each writing thread holds at most one).
TemporarySlot* claim_slot(const std::string& path) {
    if (path.size() >= sizeof TemporarySlot::path) return nullptr;
    for (;;) {
        for (TemporarySlot& slot : g_temporaries) {
            int free = kFree;
            if (slot.state.compare_exchange_strong(free, kCreating)) {
                std::memcpy(slot.path, path.c_str(), path.size() + 1);
                return &slot;
            }
        }
        std::this_thread::yield();
    }
}

// Owns an open temporary: registered for the signal handler, removed unless committed.
class Temporary {
  public:
    // Creates a fresh temporary for `path`, readable and writable as a new file would be (0666
    // less the umask), or `mode` when given.
    Temporary(const fs::path& path, std::optional<mode_t> mode) {
        std::random_device random;
        std::uniform_int_distribution<size_t> pick(0, kUniqueAlphabet.size() - 1);
        for (int attempt = 0; attempt < 100; ++attempt) {
            std::string unique;
            for (size_t i = 0; i < kUniqueLength; ++i) unique += kUniqueAlphabet[pick(random)];
            path_ = temporary_path_for(path, unique);
            const InterruptsBlocked blocked;
            slot_ = claim_slot(path_.native());
            if (g_stopping.load()) {
                // An interrupt is being handled on another thread: the process is ending, and no
                // temporary may be created once the handler has looked at the slots.
                release();
                for (;;) ::pause();
            }
            fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
            const int error = errno;
            if (slot_) slot_->state.store(fd_ >= 0 ? kHeld : kFree);
            if (fd_ >= 0) break;
            slot_ = nullptr;
            if (error != EEXIST) fail(path, "cannot write", error);
        }
        if (fd_ < 0) fail(path, "cannot create a temporary", EEXIST);
        if (mode && ::fchmod(fd_, *mode & 0777) != 0) {
            const int error = errno;
            discard();
            fail(path, "cannot write", error);
        }
    }
    ~Temporary() { discard(); }
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;

    int fd() const { return fd_; }
    // Closes the file; returns 0 or errno.
    int close() {
        const int result = ::close(fd_);
        fd_ = -1;
        return result == 0 ? 0 : errno;
    }
    // Renames the temporary to `target`; returns 0 or errno. The temporary is gone either way.
    int commit(const fs::path& target) {
        const int result = std::rename(path_.c_str(), target.c_str()) == 0 ? 0 : errno;
        if (result == 0) {
            committed_ = true;
            release();
        }
        return result;
    }

  private:
    void discard() {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
        if (!committed_ && !path_.empty()) {
            ::unlink(path_.c_str());
            committed_ = true;
        }
        release();
    }
    void release() {
        if (slot_) slot_->state.store(kFree);
        slot_ = nullptr;
    }

    fs::path path_;
    int fd_ = -1;
    bool committed_ = false;
    TemporarySlot* slot_ = nullptr;
};

// Writes all of `contents`; returns 0 or errno (ENOSPC when write makes no progress).
int write_all(int fd, std::string_view contents) {
    const char* data = contents.data();
    size_t left = contents.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, data, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? errno : ENOSPC;
        data += n;
        left -= size_t(n);
    }
    return 0;
}

// The output's name as it appears in its temporaries' names.
std::string embedded_name(const std::string& name) {
    if (name.size() <= kMaxEmbeddedName) return name;
    uint32_t hash = 2166136261u;  // FNV-1a
    for (const char c : name) hash = (hash ^ uint8_t(c)) * 16777619u;
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", hash);
    return name.substr(0, kMaxEmbeddedName) + "~" + hex;
}

// If `name` is a temporary of the output embedded as `embedded` (".EMBEDDED.tmp-PID-UNIQUE"),
// its pid; else 0.
pid_t temporary_owner(const std::string& name, const std::string& embedded) {
    const std::string prefix = "." + embedded + ".tmp-";
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
    const std::string_view rest = std::string_view(name).substr(prefix.size());
    const size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string_view::npos || dash > 9) return 0;
    const std::string_view digits = rest.substr(0, dash), unique = rest.substr(dash + 1);
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) return 0;
    if (unique.size() != kUniqueLength ||
        !std::all_of(unique.begin(), unique.end(), [](char c) { return kUniqueAlphabet.find(c) != std::string_view::npos; })) {
        return 0;
    }
    return pid_t(std::stol(std::string(digits)));
}

// Removes temporaries of `path` left by runs that were killed (their process is gone). A folder
// is listed once per process: the names that look like anyone's temporary are kept for the
// later outputs in it.
void remove_leftovers(const fs::path& path) {
    static std::mutex mutex;
    static std::map<std::string, std::vector<std::string>> candidates_by_folder;
    const std::lock_guard lock(mutex);
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    auto [it, fresh] = candidates_by_folder.try_emplace(folder.string());
    std::vector<std::string>& candidates = it->second;
    if (fresh) {
        if (DIR* d = ::opendir(folder.c_str())) {
            while (const dirent* entry = ::readdir(d)) {
                const std::string name = entry->d_name;
                if (name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos) {
                    candidates.push_back(name);
                }
            }
            ::closedir(d);
        }
    }
    const std::string embedded = embedded_name(path.filename().string());
    std::erase_if(candidates, [&](const std::string& name) {
        const pid_t owner = temporary_owner(name, embedded);
        if (owner <= 0 || owner == ::getpid()) return false;
        if (::kill(owner, 0) == 0 || errno != ESRCH) return false;  // still running (or not ours to ask)
        ::unlink((folder / name).c_str());  // unlink never follows a link
        return true;
    });
}

// Writes a character device or FIFO as it is: opened for writing, never created or truncated.
void write_in_place(const fs::path& path, std::string_view contents, bool through_link) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | (through_link ? 0 : O_NOFOLLOW));
    if (fd < 0) fail(path, "cannot write", errno);
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !(S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode))) {
        ::close(fd);
        refuse(path, "changed while being opened; not written");
    }
    int error = write_all(fd, contents);
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error != 0) fail(path, "cannot write", error);
}

// The descriptor `path` names when it is /dev/stdout, /dev/stderr, /dev/fd/N or /proc/self/fd/N
// and that descriptor is open, else -1: writing to it keeps what the shell set up (a pipe, a
// file opened for appending) instead of replacing the file behind it.
int named_descriptor(const fs::path& path) {
    const std::string& s = path.native();
    int fd = -1;
    if (s == "/dev/stdout") fd = STDOUT_FILENO;
    if (s == "/dev/stderr") fd = STDERR_FILENO;
    for (const std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
        const std::string_view digits = std::string_view(s).substr(std::min(s.size(), prefix.size()));
        if (s.starts_with(prefix) && !digits.empty() && digits.size() <= 6 &&
            std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
            fd = std::stoi(std::string(digits));
        }
    }
    return fd >= 0 && ::fcntl(fd, F_GETFD) != -1 ? fd : -1;
}

// Refuses what cannot be an output; true when `kind` is written in place.
bool written_in_place(const fs::path& path, mode_t kind) {
    if (S_ISCHR(kind) || S_ISFIFO(kind)) return true;
    if (S_ISDIR(kind)) refuse(path, "is a folder; not replaced");
    if (S_ISBLK(kind)) refuse(path, "is a block device; not written");
    if (S_ISSOCK(kind)) refuse(path, "is a socket; not written");
    return false;
}

// Replaces (or creates) the regular file `path` through a temporary beside it.
void write_replacing(const fs::path& path, std::string_view contents, const struct stat* existing) {
    if (existing) {
        // Root may write anything, so for root the mode bits decide.
        int error = 0;
        if (::geteuid() == 0) {
            if ((existing->st_mode & 0222) == 0) error = EACCES;
        } else if (::faccessat(AT_FDCWD, path.c_str(), W_OK, AT_EACCESS) != 0) {
            error = errno;
        }
        if (error == EACCES) refuse(path, "is read-only; not replaced (make it writable or remove it)");
        if (error != 0) fail(path, "cannot write", error);
    }
    remove_leftovers(path);
    Temporary temp(path, existing ? std::optional<mode_t>(existing->st_mode) : std::nullopt);
    if (const int error = write_all(temp.fd(), contents)) fail(path, "cannot write", error);
    if (const int error = temp.close()) fail(path, "cannot write", error);
    if (const int error = temp.commit(path)) fail(path, "cannot rename into place", error);
}

}  // namespace

void install_interrupt_cleanup() {
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal_number, remove_temporary_and_exit);
    std::signal(SIGXFSZ, SIG_IGN);
    std::signal(SIGPIPE, SIG_IGN);
}

fs::path temporary_path_for(const fs::path& path, std::string_view unique) {
    std::string fresh;
    if (unique.empty()) {
        std::random_device random;
        std::uniform_int_distribution<size_t> pick(0, kUniqueAlphabet.size() - 1);
        for (size_t i = 0; i < kUniqueLength; ++i) fresh += kUniqueAlphabet[pick(random)];
        unique = fresh;
    }
    return path.parent_path() / ("." + embedded_name(path.filename().string()) + ".tmp-" +
                                 std::to_string(::getpid()) + "-" + std::string(unique));
}

std::optional<FileIdentity> file_identity(const fs::path& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return std::nullopt;
    return FileIdentity{info.st_dev, info.st_ino};
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    if (!path.parent_path().empty()) {
        std::error_code ec;
        fs::create_directories(path.parent_path(), ec);
        if (ec) fail(path.parent_path(), "cannot create folder", ec.value());
    }
    if (const int fd = named_descriptor(path); fd >= 0) {
        if (const int error = write_all(fd, contents)) fail(path, "cannot write", error);
        return;
    }
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) {
        if (errno != ENOENT) fail(path, "cannot write", errno);
        write_replacing(path, contents, nullptr);
        return;
    }
    if (S_ISLNK(info.st_mode)) {
        // A link is followed: the file it leads to is the output.
        struct stat target {};
        if (::stat(path.c_str(), &target) != 0) {
            if (errno == ENOENT) refuse(path, "is a symbolic link to a missing file; not followed");
            fail(path, "cannot write", errno);
        }
        if (written_in_place(path, target.st_mode)) {
            write_in_place(path, contents, true);
            return;
        }
        std::error_code ec;
        const fs::path resolved = fs::canonical(path, ec);
        if (ec) fail(path, "cannot follow the link", ec.value());
        write_file_atomically(resolved, contents);
        return;
    }
    if (written_in_place(path, info.st_mode)) {
        write_in_place(path, contents, false);
        return;
    }
    write_replacing(path, contents, &info);
}

}  // namespace inkline::output
