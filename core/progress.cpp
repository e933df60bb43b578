#include <refract/core/progress.h>

#include <cmath>
#include <cstdio>

#include <unistd.h>

namespace refract {
namespace {

std::string seconds(double s) {
    char buf[32];
    if (s < 60) std::snprintf(buf, sizeof buf, "%.1f s", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
    else std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s) / 3600, static_cast<int>(s) / 60 % 60);
    return buf;
}

}  // namespace

std::string progress_line(const std::string& label, const std::string& unit, std::int64_t done, std::int64_t total,
                          double elapsed_s) {
    if (total <= 0) return label + ": " + seconds(elapsed_s) + " elapsed";
    std::string s = label + ": " + std::to_string(done) + " / " + std::to_string(total) + (unit.empty() ? "" : " " + unit) +
                    " (" + std::to_string(100 * done / total) + "%), " + seconds(elapsed_s) + " elapsed";
    if (done > 0 && done < total) s += ", about " + seconds(elapsed_s * static_cast<double>(total - done) / done) + " left";
    return s;
}

bool stderr_is_terminal() { return isatty(STDERR_FILENO) != 0; }

Progress::Progress(std::string label, std::string unit, std::int64_t total, bool enabled)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), enabled_(enabled),
      t0_(std::chrono::steady_clock::now()), last_(t0_) {
    if (!enabled_) return;
    // A ticker redraws twice a second: the elapsed time moves while no unit finishes.
    ticker_ = std::thread([this] {
        std::unique_lock<std::mutex> g(mutex_);
        while (!finished_) {
            wake_.wait_for(g, std::chrono::milliseconds(500));
            if (!finished_) {
                g.unlock();
                draw(true);
                g.lock();
            }
        }
    });
}

Progress::~Progress() { finish(); }

void Progress::set(std::int64_t done) {
    done_ = done;
    draw(false);
}

void Progress::add(std::int64_t n) {
    done_ += n;
    draw(false);
}

void Progress::set_total(std::int64_t total) { total_ = total; }

void Progress::message(const std::string& text) {
    {
        std::lock_guard<std::mutex> g(mutex_);
        std::fprintf(stderr, "%s%s\n", drawn_ && !finished_ ? "\r\033[K" : "", text.c_str());
        std::fflush(stderr);
    }
    draw(true);
}

void Progress::draw(bool force) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> g(mutex_);
    if (finished_) return;
    const auto now = std::chrono::steady_clock::now();
    const double el = std::chrono::duration<double>(now - t0_).count();
    if (el < 1.0 || (!force && now - last_ < std::chrono::milliseconds(200))) return;
    last_ = now;
    const std::string text = progress_line(label_, unit_, done_, total_, el);
    std::fprintf(stderr, "\r%s\033[K", text.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void Progress::finish() {
    {
        std::lock_guard<std::mutex> g(mutex_);
        if (finished_) return;
        finished_ = true;
        if (drawn_) {
            std::fprintf(stderr, "\r\033[K");
            std::fflush(stderr);
        }
    }
    wake_.notify_all();
    if (ticker_.joinable()) ticker_.join();
}

}  // namespace refract
