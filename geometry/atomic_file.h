#pragma once
// Writing a file so that it is never seen half-written, and never through a planted link:
// the bytes go to a temporary in the target's directory, created exclusively
// (O_CREAT | O_EXCL | O_NOFOLLOW) under an unpredictable name `.refract-tmp-<16 hex>`
// (plus the target's extension, for writers that choose the format by it), then renamed
// onto the target. The temporary is removed on every error path, when a TempFile is
// destroyed uncommitted, and on SIGINT/SIGTERM once install_temp_cleanup() has run (a
// kill -9 can leave one behind: its name says what it is). docs/limits.md.
#include <string>

namespace refract {

class TempFile {
public:
    // Creates the temporary beside `target`; InputError naming the target when the
    // directory is missing or not writable.
    explicit TempFile(const std::string& target, bool keep_extension = false);
    ~TempFile();
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    const std::string& path() const { return path_; }  // the temporary (empty, ready to write)
    // Renames the temporary onto the target (an existing target is replaced; a link there is
    // replaced, not followed). InputError naming the target on failure.
    void commit();

private:
    std::string target_, path_;
    int slot_ = -1;  // in the signal-cleanup registry
    bool committed_ = false;
};

// `bytes` into `path` through a TempFile; InputError naming the path on any failure
// (disk full included), leaving no temporary and the old file, if any, untouched.
void write_file_atomic(const std::string& path, const std::string& bytes);

// 16 hex digits from the system's random source: unpredictable temporary names.
std::string random_token();

// Installs SIGINT and SIGTERM handlers that remove the live temporaries, then end the
// process with the signal's default action. Idempotent.
void install_temp_cleanup();

}  // namespace refract
