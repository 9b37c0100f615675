#pragma once
/// @file units.h
/// Constants and angle conversions for the edges of core (files, command line, screen). Everything
/// inside core is SI: Pa, m, rad, N, N·m. The thesis's other units (kPa, kN/m^(n+1), kN/m³) are
/// converted by the factors of the field tables that read them (SoilField in
/// core/soil/soil_parameters.cpp; docs/model.md, "Units").

#include <numbers>

namespace terra::units {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kGravity = 9.81;  ///< [m/s²] the thesis's value ("W = 6 kg" = 58.86 N)

constexpr double degToRad(double deg) { return deg * kPi / 180.0; }
constexpr double radToDeg(double rad) { return rad * 180.0 / kPi; }

}  // namespace terra::units
