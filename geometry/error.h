#pragma once
// Bad input is reported by throwing InputError with one line that names the file, field
// or parameter; the command line turns it into that line on stderr and exit code 2.
#include <cstdio>
#include <stdexcept>
#include <string>

#include <refract/geometry/format.h>

namespace refract {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A number as an error message shows it (up to 10 significant digits; geometry/format.h).
inline std::string format_value(double v) { return format_significant(v, 10); }

}  // namespace refract
