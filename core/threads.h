#pragma once
// Worker threads: every parallel pass takes its count from here (docs/limits.md).

namespace refract {

constexpr int kMaxThreads = 1024;

// The number of worker threads for `requested`: 0 means all cores; InputError naming
// --threads when it lies outside [0, kMaxThreads].
int worker_threads(int requested);

}  // namespace refract
