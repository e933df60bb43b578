#pragma once
// Mathematical constants shared by the layers (C++17 has no std::numbers).

namespace refract {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace refract
