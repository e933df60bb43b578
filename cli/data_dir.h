#pragma once
// The data refract installs under PREFIX/share/refract (scenes/, with the validation suite
// in scenes/validation): found relative to the executable, so that an installed `refract`
// run outside the checkout uses its own copy.
#include <string>

namespace refract::cli {

// The validation scenes directory: `given` when the user passed --scenes; else
// scenes/validation when that is a directory (run from the checkout); else the installed
// copy, <executable>/../share/refract/scenes/validation, when present; else `given`.
std::string validation_scenes(const std::string& given, bool passed);

}  // namespace refract::cli
