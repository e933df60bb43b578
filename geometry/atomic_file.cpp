#include <refract/geometry/atomic_file.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <refract/geometry/error.h>
#include <refract/geometry/signal_cleanup.h>

namespace refract {

// What the signal handler needs to remove a private directory: descriptors and its name
// only (unlinkat, fstatat, getdents: async-signal-safe), no path a rename could redirect.
struct PrivateDir::Live {
    int parent = -1, dir = -1;
    char name[64] = {};
};

namespace {

bool same_file(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

// Removes the private directory `name` in `parent` when it is still the one open as `dir`
// (another user may have renamed it and put something else under its name).
void remove_private_dir(int parent, int dir, const char* name) {
    struct stat mine {}, there {};
    if (::fstat(dir, &mine) == 0 && ::fstatat(parent, name, &there, AT_SYMLINK_NOFOLLOW) == 0 &&
        same_file(mine, there))
        ::unlinkat(parent, name, AT_REMOVEDIR);
}

std::string error_text(int err) { return std::strerror(err); }

}  // namespace

std::string random_token() {
    std::random_device rd;  // getrandom(2): unpredictable
    const unsigned long long v = (static_cast<unsigned long long>(rd()) << 32) ^ rd();
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", v);
    return buf;
}

void PrivateDir::on_signal(void* p) {
    const Live& l = *static_cast<const Live*>(p);
    remove_entries_now(l.dir);
    remove_private_dir(l.parent, l.dir, l.name);
}

PrivateDir::PrivateDir(const std::string& target) : live_(std::make_unique<Live>()) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(target).parent_path().empty() ? fs::path(".") : fs::path(target).parent_path();
    parent_ = ::open(dir.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (parent_ < 0) throw InputError(target + ": cannot create a file in " + dir.string() + ": " + error_text(errno));
    for (int attempt = 0; attempt < 16 && dir_ < 0; ++attempt) {
        const std::string name = ".refract-tmp-" + random_token();
        if (::mkdirat(parent_, name.c_str(), 0700) != 0) {
            if (errno == EEXIST) continue;
            const int err = errno;
            ::close(parent_);
            throw InputError(target + ": cannot create a file in " + dir.string() + ": " + error_text(err));
        }
        // Opened without following a link and checked to be ours: between mkdirat and
        // openat another user may have renamed it and put another in its place.
        const int d = ::openat(parent_, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        struct stat st {};
        if (d >= 0 && ::fstat(d, &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == ::geteuid() &&
            ::fchmod(d, 0700) == 0) {  // 0700 whatever the umask or a default ACL gave it
            dir_ = d;
            name_ = name;
        } else if (d >= 0) {
            ::close(d);
        }
    }
    if (dir_ < 0) {
        ::close(parent_);
        throw InputError(target + ": cannot create a file in " + dir.string() + ": no private temporary directory");
    }
    path_ = (dir / name_).string();
    live_->parent = parent_;
    live_->dir = dir_;
    std::memcpy(live_->name, name_.c_str(), name_.size() + 1);
    slot_ = add_signal_cleanup(on_signal, live_.get());
}

PrivateDir::~PrivateDir() {
    remove_signal_cleanup(slot_);
    remove_entries_now(dir_);
    remove_private_dir(parent_, dir_, name_.c_str());
    ::close(dir_);
    ::close(parent_);
}

void PrivateDir::move_out(const std::string& name, const std::string& target_name, const std::string& target) const {
    struct stat st {};
    if (::fstatat(dir_, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
        throw InputError(target + ": the temporary " + path_ + "/" + name + " is missing or not a regular file; not written");
    if (::renameat(dir_, name.c_str(), parent_, target_name.c_str()) != 0)
        throw InputError(target + ": cannot write: " + error_text(errno));
}

TempFile::TempFile(const std::string& target) : target_(target) {
    file_name_ = std::filesystem::path(target).filename().string();
    if (file_name_.empty() || file_name_ == "." || file_name_ == "..") throw InputError(target + ": not a file name");
    dir_ = std::make_unique<PrivateDir>(target);
    path_ = dir_->path() + "/" + file_name_;
    fd_ = ::openat(dir_->fd(), file_name_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0) {
        const int err = errno;
        const std::string where = std::filesystem::path(dir_->path()).parent_path().string();
        dir_.reset();
        throw InputError(target + ": cannot create a file in " + where + ": " + error_text(err));
    }
}

TempFile::~TempFile() {
    if (fd_ >= 0) ::close(fd_);
}  // the private directory goes with what it holds

void TempFile::commit() {
    if (!dir_) throw InputError(target_ + ": cannot write: the temporary is gone");
    std::unique_ptr<PrivateDir> dir = std::move(dir_);  // removed at the end of this call, whatever happens
    const auto fail = [&](const std::string& why) { throw InputError(target_ + ": " + why); };
    struct stat written {}, named {};
    if (::fstat(fd_, &written) != 0) fail("cannot write: " + error_text(errno));
    const int closed = ::close(fd_);  // a deferred write error (NFS, quota) shows here
    fd_ = -1;
    if (closed != 0) fail("cannot write: " + error_text(errno));
    if (::fstatat(dir->fd(), file_name_.c_str(), &named, AT_SYMLINK_NOFOLLOW) != 0 || !same_file(written, named))
        fail("the temporary " + path_ + " was replaced during the write; not written");
    if (::renameat(dir->fd(), file_name_.c_str(), dir->parent_, file_name_.c_str()) != 0)
        fail("cannot write: " + error_text(errno));
    // The name renamed may have been swapped between the check and the rename (only by this
    // user: the directory is private): what now stands at the target must be the file written.
    struct stat placed {};
    if (::fstatat(dir->parent_, file_name_.c_str(), &placed, AT_SYMLINK_NOFOLLOW) == 0 && !same_file(written, placed)) {
        ::unlinkat(dir->parent_, file_name_.c_str(), 0);
        fail("the temporary " + path_ + " was replaced during the write; not written");
    }
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
    TempFile tmp(path);
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(tmp.fd(), bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw InputError(path + ": cannot write: " + error_text(n < 0 ? errno : ENOSPC));  // disk full
        done += static_cast<size_t>(n);
    }
    tmp.commit();
}

int open_own_file(const std::string& path, int flags, const std::string& what, int at) {
    const int fd = ::openat(at, path.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int err = errno;
        if (err == ENOENT) return -1;
        if (err == ELOOP) throw InputError(path + ": " + what + " is a symbolic link, not a file refract wrote; refused");
        throw InputError(path + ": cannot open " + what + ": " + error_text(err));
    }
    struct stat st {};
    const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    if (!regular || st.st_nlink != 1) {
        ::close(fd);
        throw InputError(path + ": " + what + (regular ? " has other names (hard links)" : " is not a regular file") +
                         ", not a file refract wrote; refused");
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    return fd;
}

std::string read_own_file(const std::string& path, const std::string& what, int at) {
    std::string text;
    const int fd = open_own_file(path, O_RDONLY, what, at);
    if (fd < 0) return text;
    char buf[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int err = errno;
            ::close(fd);
            throw InputError(path + ": cannot read " + what + ": " + error_text(err));
        }
        if (n == 0) break;
        text.append(buf, static_cast<size_t>(n));
    }
    ::close(fd);
    return text;
}

}  // namespace refract
