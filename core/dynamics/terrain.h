#pragma once
/// @file terrain.h
/// Flat deformable terrain made of soil patches: a base soil everywhere, overridden by
/// axis-aligned rectangles (the last listed patch that contains a point wins), so a scenario can
/// cross from sandy loam into clayey soil. The surface is the plane z = 0.

#include <limits>
#include <string>
#include <vector>

#include "core/soil/soil_parameters.h"

namespace terra::dynamics {

/// A rectangle of one soil, x_min ≤ x < x_max and y_min ≤ y < y_max [m] (open sides: ±inf).
struct SoilPatch {
    soil::SoilParameters soil;
    double x_min_m = -std::numeric_limits<double>::infinity();
    double x_max_m = std::numeric_limits<double>::infinity();
    double y_min_m = -std::numeric_limits<double>::infinity();
    double y_max_m = std::numeric_limits<double>::infinity();

    bool contains(double x_m, double y_m) const {
        return x_m >= x_min_m && x_m < x_max_m && y_m >= y_min_m && y_m < y_max_m;
    }
};

/// The soil map.
struct Terrain {
    soil::SoilParameters base;       ///< soil outside every patch
    std::vector<SoilPatch> patches;  ///< later patches cover earlier ones

    /// Index of the soil at (x, y): 0 for the base, i + 1 for patches[i].
    int soilIndexAt(double x_m, double y_m) const {
        for (int i = static_cast<int>(patches.size()) - 1; i >= 0; --i) {
            if (patches[i].contains(x_m, y_m)) return i + 1;
        }
        return 0;
    }
    /// The soil of index `index` (see soilIndexAt).
    const soil::SoilParameters& soil(int index) const {
        return index == 0 ? base : patches[index - 1].soil;
    }
    int soilCount() const { return static_cast<int>(patches.size()) + 1; }
};

}  // namespace terra::dynamics
