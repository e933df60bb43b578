#pragma once
// The message of the InputError that f throws ("" if none), for the tests of refused input.
#include <string>

#include <refract/geometry/error.h>

namespace refract::test {
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}
}  // namespace refract::test
