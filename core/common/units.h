#pragma once
/// @file units.h
/// Unit conversions used at the edges of core (files, command line, screen). Everything inside
/// core is SI: Pa, m, rad, N, N·m. The thesis's units (kPa, deg, kN/m^(n+1), kN/m³) are converted
/// here and nowhere else.

#include <numbers>

namespace terra::units {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kGravity = 9.81;  ///< [m/s²] the thesis's value ("W = 6 kg" = 58.86 N)

constexpr double degToRad(double deg) { return deg * kPi / 180.0; }
constexpr double radToDeg(double rad) { return rad * 180.0 / kPi; }
constexpr double kiloToUnit(double kilo) { return kilo * 1e3; }  ///< kPa→Pa, kN→N, kN/m³→N/m³
constexpr double unitToKilo(double unit) { return unit * 1e-3; }

}  // namespace terra::units
