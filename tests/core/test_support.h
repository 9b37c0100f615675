#pragma once
/// @file test_support.h
/// What many core tests share (one definition each, so the unity build's batches do not clash):
/// the shipped presets and sandy loam on wheel A, degrees, a substring test and the message of a
/// rejected argument.

#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/analysis/analysis.h"
#include "core/io/parameters_json.h"

namespace terra::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;  ///< [rad/deg]
inline constexpr double kExact = 1e-12;                   ///< exact arithmetic up to rounding

/// The presets shipped in resources/ of this tree.
inline const io::PresetLocations kLocations{{TERRA_RESOURCE_DIR}};

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// The shipped sandy loam on the shipped wheel A, at the default operating conditions.
inline analysis::Inputs sandyLoamOnA() {
    analysis::Inputs in;
    in.soil = io::resolveSoil(kLocations, "sandy-loam").value();
    in.wheel = io::resolveWheel(kLocations, "A").value();
    return in;
}

/// The message of the std::invalid_argument that `f` throws, or "(no exception)".
inline std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no exception)";
}

}  // namespace terra::testing
