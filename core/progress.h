#pragma once
// One progress line on stderr for the commands that can run longer than a few seconds:
// done / total, percent, elapsed time and an estimate of the time left, redrawn in place
// at most a few times a second; with no total (work of unknown size), the elapsed time,
// redrawn by a ticker thread. Quiet unless enabled (the CLI enables it when stderr is a
// terminal), and silent during the first second. Thread-safe.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace refract {

// The line itself (no carriage return): "LABEL: 120 / 400 UNIT (30%), 3.1 s elapsed, about
// 7.2 s left"; total 0: "LABEL: 3.1 s elapsed".
std::string progress_line(const std::string& label, const std::string& unit, std::int64_t done, std::int64_t total,
                          double elapsed_s);

// True when stderr is a terminal.
bool stderr_is_terminal();

class Progress {
public:
    Progress(std::string label, std::string unit, std::int64_t total, bool enabled);
    ~Progress();  // finish()
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void set(std::int64_t done);
    void add(std::int64_t n = 1);
    void set_total(std::int64_t total);
    // Writes `text` and a newline to stderr above the progress line (which is redrawn).
    void message(const std::string& text);
    // Clears the line (nothing is left on the terminal); further updates print nothing.
    void finish();

private:
    void draw(bool force);
    std::string label_, unit_;
    std::atomic<std::int64_t> total_, done_{0};
    bool enabled_;
    std::chrono::steady_clock::time_point t0_, last_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool finished_ = false, drawn_ = false;
    std::thread ticker_;
};

}  // namespace refract
