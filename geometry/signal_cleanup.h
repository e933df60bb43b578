#pragma once
// What SIGINT and SIGTERM leave behind: nothing refract made for the work in progress.
// install_temp_cleanup() installs handlers that run the registered cleanups (the last
// registered first: a child process is killed before its directory is removed), remove
// the live temporaries (geometry/atomic_file.h), then end the process by the signal's
// default action. Cleanups run inside the signal handler: they may only make
// async-signal-safe calls (kill, waitpid, unlinkat, the remove_tree_now below).
// docs/limits.md "Files".
#include <signal.h>

namespace refract {

// Installs the SIGINT and SIGTERM handlers. Idempotent.
void install_temp_cleanup();

// Registers `hook(data)` to run on SIGINT/SIGTERM: a handle for remove_signal_cleanup, or
// -1 when the table (1024 entries) is full (the cleanup is then not made on a signal).
int add_signal_cleanup(void (*hook)(void*), void* data);
void remove_signal_cleanup(int handle);

// Removes `path` and, when it is a directory, everything under it, following no link
// (a link is removed, not followed; at most 32 levels). Async-signal-safe: for cleanups.
void remove_tree_now(const char* path);
// Removes everything in the directory open as `dir_fd` (read access), as remove_tree_now.
void remove_entries_now(int dir_fd);

// A directory tree removed on SIGINT/SIGTERM while this object lives (a case directory
// being written, a child program's temporary directory). Does nothing at the end of its
// scope: call release() to stop watching it, or let the owner remove it.
class TreeOnSignal {
public:
    explicit TreeOnSignal(const char* path);  // `path` is copied
    ~TreeOnSignal() { release(); }
    TreeOnSignal(const TreeOnSignal&) = delete;
    TreeOnSignal& operator=(const TreeOnSignal&) = delete;
    void release();

private:
    char path_[4096];
    int handle_ = -1;
};

// Blocks SIGINT and SIGTERM in the calling thread for its scope (fork, then registering
// the child); the previous mask is restored at its end. In a forked child, before exec,
// in_child() sets both signals' default actions (unless ignored) and restores the mask
// (async-signal-safe).
class SignalsHeld {
public:
    SignalsHeld();
    ~SignalsHeld();
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;
    void in_child() const;

private:
    sigset_t old_;
};

}  // namespace refract
