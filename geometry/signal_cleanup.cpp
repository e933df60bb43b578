#include <refract/geometry/signal_cleanup.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <csignal>
#include <cstring>

#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace refract {

namespace {

// The cleanups, for the signal handler: fixed slots it can read without locking or
// allocating. A slot is claimed (1), filled, then made ready (2); `seq` orders them.
constexpr int kSlots = 1024;
struct Slot {
    std::atomic<int> state{0};
    std::atomic<std::uint64_t> seq{0};
    void (*hook)(void*) = nullptr;
    void* data = nullptr;
};
std::array<Slot, kSlots> g_slots;
std::atomic<std::uint64_t> g_seq{0};
std::atomic<bool> g_cleaning{false};

extern "C" void on_signal(int sig) {
    if (g_cleaning.exchange(true)) return;  // another thread is cleaning up, then ends the process
    {
        // The last registered first: a process is killed before its directory is removed.
        std::uint64_t below = UINT64_MAX;
        for (;;) {
            int best = -1;
            std::uint64_t best_seq = 0;
            for (int k = 0; k < kSlots; ++k) {
                const Slot& s = g_slots[static_cast<size_t>(k)];
                if (s.state.load() != 2) continue;
                const std::uint64_t q = s.seq.load();
                if (q < below && (best < 0 || q > best_seq)) {
                    best = k;
                    best_seq = q;
                }
            }
            if (best < 0) break;
            below = best_seq;
            const Slot& s = g_slots[static_cast<size_t>(best)];
            s.hook(s.data);
        }
    }
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, nullptr);
    ::raise(sig);  // ends the process once the handler returns (the signal is blocked inside it)
}

// What getdents64 returns.
struct Dirent64 {
    std::uint64_t ino;
    std::int64_t off;
    unsigned short reclen;
    unsigned char type;
    char name[1];
};

void remove_at(int parent, const char* name, int depth);

void remove_entries(int fd, int depth) {
    alignas(8) char buf[1024];
    for (int pass = 0; pass < 64; ++pass) {  // again while a pass removed something
        ::lseek(fd, 0, SEEK_SET);
        bool removed = false;
        for (;;) {
            const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
            if (n <= 0) break;
            for (long off = 0; off < n;) {
                const auto* d = reinterpret_cast<const Dirent64*>(buf + off);
                off += d->reclen;
                if (std::strcmp(d->name, ".") == 0 || std::strcmp(d->name, "..") == 0) continue;
                remove_at(fd, d->name, depth);
                removed = true;
            }
        }
        if (!removed) return;
    }
}

void remove_at(int parent, const char* name, int depth) {
    if (::unlinkat(parent, name, 0) == 0) return;
    if ((errno != EISDIR && errno != EPERM) || depth >= 32) return;
    const int fd = ::openat(parent, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return;
    remove_entries(fd, depth + 1);
    ::close(fd);
    ::unlinkat(parent, name, AT_REMOVEDIR);
}

void remove_tree_hook(void* path) { remove_tree_now(static_cast<const char*>(path)); }

}  // namespace

void install_temp_cleanup() {
    static std::atomic<bool> done{false};
    if (done.exchange(true)) return;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);  // one cleanup at a time in this thread
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

int add_signal_cleanup(void (*hook)(void*), void* data) {
    for (int k = 0; k < kSlots; ++k) {
        Slot& s = g_slots[static_cast<size_t>(k)];
        int expected = 0;
        if (s.state.compare_exchange_strong(expected, 1)) {
            s.hook = hook;
            s.data = data;
            s.seq.store(++g_seq);
            s.state.store(2);
            return k;
        }
    }
    return -1;
}

void remove_signal_cleanup(int handle) {
    if (handle >= 0 && handle < kSlots) g_slots[static_cast<size_t>(handle)].state.store(0);
}

void remove_tree_now(const char* path) { remove_at(AT_FDCWD, path, 0); }

void remove_entries_now(int dir_fd) { remove_entries(dir_fd, 1); }

TreeOnSignal::TreeOnSignal(const char* path) {
    const size_t n = std::strlen(path);
    if (n >= sizeof path_) return;  // not watched: too long for the table
    std::memcpy(path_, path, n + 1);
    handle_ = add_signal_cleanup(remove_tree_hook, path_);
}

void TreeOnSignal::release() {
    remove_signal_cleanup(handle_);
    handle_ = -1;
}

SignalsHeld::SignalsHeld() {
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &block, &old_);
}

SignalsHeld::~SignalsHeld() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

void SignalsHeld::in_child() const {
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    for (const int sig : {SIGINT, SIGTERM}) {
        struct sigaction now {};
        if (sigaction(sig, nullptr, &now) == 0 && now.sa_handler != SIG_IGN) sigaction(sig, &dfl, nullptr);
    }
    sigprocmask(SIG_SETMASK, &old_, nullptr);
}

}  // namespace refract
