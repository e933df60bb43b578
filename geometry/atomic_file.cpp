#include <refract/geometry/atomic_file.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <fcntl.h>
#include <unistd.h>

#include <refract/geometry/error.h>

namespace refract {

namespace {

// Live temporaries, for the signal handler (which may only use async-signal-safe calls:
// it reads these fixed buffers and calls unlink).
constexpr int kSlots = 256;
constexpr size_t kPathMax = 4096;
std::array<std::atomic<bool>, kSlots> g_used{};
std::array<std::array<char, kPathMax>, kSlots> g_paths{};

int register_path(const std::string& p) {
    if (p.size() >= kPathMax) return -1;
    for (int k = 0; k < kSlots; ++k) {
        bool expected = false;
        if (g_used[static_cast<size_t>(k)].compare_exchange_strong(expected, true)) {
            std::memcpy(g_paths[static_cast<size_t>(k)].data(), p.c_str(), p.size() + 1);
            return k;
        }
    }
    return -1;  // registry full: the temporary is still removed on every other path
}

void unregister(int slot) {
    if (slot >= 0) g_used[static_cast<size_t>(slot)].store(false);
}

extern "C" void remove_temporaries(int sig) {
    for (int k = 0; k < kSlots; ++k)
        if (g_used[static_cast<size_t>(k)].load()) ::unlink(g_paths[static_cast<size_t>(k)].data());
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

std::string random_token() {
    std::random_device rd;  // getrandom(2): unpredictable
    const unsigned long long v = (static_cast<unsigned long long>(rd()) << 32) ^ rd();
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", v);
    return buf;
}

TempFile::TempFile(const std::string& target, bool keep_extension) : target_(target) {
    namespace fs = std::filesystem;
    const fs::path t(target);
    const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    const std::string ext = keep_extension ? t.extension().string() : std::string();
    for (int attempt = 0; attempt < 16; ++attempt) {
        const std::string p = (dir / (".refract-tmp-" + random_token() + ext)).string();
        const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd >= 0) {
            ::close(fd);
            path_ = p;
            slot_ = register_path(p);
            return;
        }
        if (errno != EEXIST)
            throw InputError(target + ": cannot create a file in " + dir.string() + ": " + std::strerror(errno));
    }
    throw InputError(target + ": cannot create a temporary file in " + dir.string());
}

TempFile::~TempFile() {
    if (!committed_ && !path_.empty()) ::unlink(path_.c_str());
    unregister(slot_);
}

void TempFile::commit() {
    if (::rename(path_.c_str(), target_.c_str()) != 0) {
        const int err = errno;
        ::unlink(path_.c_str());
        committed_ = true;  // nothing left to remove
        throw InputError(target_ + ": cannot write: " + std::strerror(err));
    }
    committed_ = true;
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
    TempFile tmp(path);
    const int fd = ::open(tmp.path().c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = errno;
            ::close(fd);
            throw InputError(path + ": cannot write: " + std::strerror(err));  // disk full: ENOSPC
        }
        done += static_cast<size_t>(n);
    }
    if (::close(fd) != 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
    tmp.commit();
}

void install_temp_cleanup() {
    static std::atomic<bool> done{false};
    if (done.exchange(true)) return;
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace refract
