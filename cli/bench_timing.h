#pragma once
// Timing helpers of `refract bench`: wall and thread-CPU clocks, medians, the load
// average line, and paired rounds (every variant once per round, in turn: A B C A B C …).
#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <sys/resource.h>

namespace refract::cli::bench {

// CPU time of this process (every thread) and of the child processes it has waited for
// (POV-Ray runs): the CPU cost of whatever ran in between two readings.
inline double process_cpu_seconds() {
    double s = 0;
    for (int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
        rusage u{};
        getrusage(who, &u);
        s += static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
    }
    return s;
}

// CPU time of this thread: the figures per core, whatever else the machine runs.
inline double thread_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double wall_seconds() {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline double minimum(const std::vector<double>& v) { return v.empty() ? 0 : *std::min_element(v.begin(), v.end()); }

inline void print_load(const char* when) {
    double load[3] = {0, 0, 0};
    if (getloadavg(load, 3) > 0)
        std::cout << "  load average " << when << ": " << std::fixed << std::setprecision(2) << load[0] << " "
                  << load[1] << " " << load[2] << "\n";
}

// Wall and CPU seconds (process_cpu_seconds) of each run of each variant.
struct Paired {
    std::vector<std::vector<double>> wall, cpu;
};

// `rounds` rounds; in each, run(k) once for every variant k in order.
inline Paired paired_runs(size_t variants, int rounds, const std::function<void(size_t)>& run) {
    Paired p;
    p.wall.resize(variants);
    p.cpu.resize(variants);
    for (int r = 0; r < rounds; ++r)
        for (size_t k = 0; k < variants; ++k) {
            const double w0 = wall_seconds(), c0 = process_cpu_seconds();
            run(k);
            p.cpu[k].push_back(process_cpu_seconds() - c0);
            p.wall[k].push_back(wall_seconds() - w0);
        }
    return p;
}

}  // namespace refract::cli::bench
