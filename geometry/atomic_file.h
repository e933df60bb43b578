#pragma once
// Writing a file so that it is never seen half-written, and never through a planted link:
// the bytes go to a file created exclusively (O_CREAT | O_EXCL | O_NOFOLLOW) inside a
// private directory `.refract-tmp-<16 hex>` (mode 0700, unpredictable name) made in the
// target's directory, and are written through that file's descriptor, never reopened by
// name; commit() checks that the name still holds that file, renames it onto the target
// (renameat on the directories' descriptors) and removes the private directory. Another
// user who can write to the target's directory can rename or replace the private
// directory, but not what it holds: every step goes through descriptors. The temporary is
// removed on every error path, when a TempFile is destroyed uncommitted, and on
// SIGINT/SIGTERM once install_temp_cleanup() has run (a kill -9 can leave one behind: its
// name says what it is). docs/limits.md "Files".
#include <memory>
#include <string>

#include <fcntl.h>

#include <refract/geometry/signal_cleanup.h>

namespace refract {

// The private directory: made beside a target, reached through its descriptor only,
// removed with all it holds when the object ends (and on SIGINT/SIGTERM).
class PrivateDir {
public:
    // Makes it in the directory of `target`; InputError naming the target when that
    // directory is missing or not writable.
    explicit PrivateDir(const std::string& target);
    ~PrivateDir();
    PrivateDir(const PrivateDir&) = delete;
    PrivateDir& operator=(const PrivateDir&) = delete;

    int fd() const { return dir_; }                   // the private directory, open
    const std::string& path() const { return path_; }  // DIR/.refract-tmp-<16 hex>, for messages
    // Renames `name`, a regular file in the private directory, onto `target_name` in the
    // target's directory. InputError naming `target` when it is not a regular file or the
    // rename fails.
    void move_out(const std::string& name, const std::string& target_name, const std::string& target) const;

private:
    struct Live;                   // what the signal handler removes
    static void on_signal(void*);  // its cleanup (geometry/signal_cleanup.h)
    int parent_ = -1, dir_ = -1;   // the target's directory, the private one
    std::string name_, path_;
    int slot_ = -1;
    std::unique_ptr<Live> live_;
    friend class TempFile;
};

class TempFile {
public:
    // Creates the private directory and the file beside `target`; InputError naming the
    // target when its directory is missing or not writable.
    explicit TempFile(const std::string& target);
    ~TempFile();
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    // The temporary's descriptor, open for reading and writing, empty: write through it.
    int fd() const { return fd_; }
    // The temporary's path (DIR/.refract-tmp-<16 hex>/NAME, NAME the target's file name),
    // for messages and tests only: nothing opens it by name.
    const std::string& path() const { return path_; }
    // Closes the descriptor, checks that the temporary's name still holds the file written
    // and renames it onto the target (an existing target is replaced; a link there is
    // replaced, not followed). InputError naming the target on failure, the temporary
    // removed.
    void commit();

private:
    std::string target_, file_name_, path_;  // file_name_: the target's, in both directories
    std::unique_ptr<PrivateDir> dir_;
    int fd_ = -1;
};

// `bytes` into `path` through a TempFile; InputError naming the path on any failure
// (disk full included), leaving no temporary and the old file, if any, untouched.
void write_file_atomic(const std::string& path, const std::string& bytes);

// 16 hex digits from the system's random source: unpredictable temporary names.
std::string random_token();

// Opens `path`, a file refract wrote itself and now reads again (a journal, a log),
// without following a link (O_NOFOLLOW) and only when it is a regular file with one name:
// the descriptor, or -1 with errno ENOENT when there is no such file. InputError naming
// `path` and `what` (e.g. "the sweep's journal") otherwise, never quoting its content.
// `flags`: O_RDONLY, or O_WRONLY | O_APPEND | O_CREAT to append. `at`: the directory
// `path` is relative to (AT_FDCWD: the working directory).
int open_own_file(const std::string& path, int flags, const std::string& what, int at = AT_FDCWD);

// The whole of a file open_own_file opens (empty when there is none); InputError as it.
std::string read_own_file(const std::string& path, const std::string& what, int at = AT_FDCWD);

}  // namespace refract
