#pragma once
// Shared by the tests: render options with a thread count.
#include <refract/core/render.h>

namespace refract::testing {

inline RenderOptions threads(int n) {
    RenderOptions o;
    o.threads = n;
    return o;
}

}  // namespace refract::testing
