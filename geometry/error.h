#pragma once
// Bad input is reported by throwing InputError with one line that names the file, field
// or parameter; the command line turns it into that line on stderr and exit code 2.
#include <stdexcept>
#include <string>

namespace refract {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace refract
