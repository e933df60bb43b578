#include <refract/geometry/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace refract {

std::string format_shortest(double v) {
    char buf[40];
    for (int digits = 6; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

std::string format_significant(double v, int significant) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", std::clamp(significant, 1, 17), v);
    return buf;
}

}  // namespace refract
