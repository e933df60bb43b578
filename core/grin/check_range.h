#pragma once
// The range check of the GRIN inputs (air state, atmosphere, refraction integral): one line
// naming the field, its range and unit, and the value given.
#include <string>

#include <refract/geometry/error.h>

namespace refract::grin {

// Throws InputError "WHERE/FIELD: must be in [LO, HI]UNIT, got V" unless lo <= v <= hi (a NaN
// fails).
inline void check_range(double v, double lo, double hi, const std::string& where, const char* field,
                        const char* unit) {
    if (!(v >= lo && v <= hi))
        throw InputError(where + "/" + field + ": must be in [" + format_value(lo) + ", " + format_value(hi) + "]" +
                         unit + ", got " + format_value(v));
}

}  // namespace refract::grin
