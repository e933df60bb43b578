#include <refract/core/threads.h>

#include <string>

#include <tbb/task_arena.h>

#include <refract/geometry/error.h>

namespace refract {

int worker_threads(int requested) {
    if (requested < 0 || requested > kMaxThreads)
        throw InputError("--threads: must be in [0, " + std::to_string(kMaxThreads) + "] (0: all cores), got " +
                         std::to_string(requested));
    return requested > 0 ? requested : tbb::this_task_arena::max_concurrency();
}

}  // namespace refract
