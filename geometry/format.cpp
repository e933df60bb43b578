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

std::string clip_echo(const std::string& text, std::size_t keep) {
    if (text.size() <= keep) return text;
    std::size_t n = keep;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // not inside a character
    return text.substr(0, n) + "\u2026(" + std::to_string(text.size()) + " bytes)";
}

}  // namespace refract
