#pragma once
// The thesis's sandy loam (Table 2.1; a0, a1, j_max from Table 2.6) and wheel A (Table 2.2), as
// the soil and wheel structs, written out by hand (not loaded through the code under test).

#include <cmath>
#include <numbers>

#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "core/gsa/batch.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"
#include "tests/core/test_support.h"

namespace terra::gsa::testing {

using terra::testing::kDeg;

inline soil::SoilParameters sandyLoam() {
    soil::SoilParameters s;
    s.name = "sandy loam";
    s.source = "Thesis Table 2.1 (after Iagnemma et al.); a0, a1, jmax from Table 2.6";
    s.sinkage_exponent = 0.7;
    s.cohesion_pa = 1.7e3;
    s.friction_angle_rad = 29.0 * kDeg;
    s.cohesive_modulus = 5.3e3;
    s.frictional_modulus = 1515e3;
    s.shear_modulus_m = 0.025;
    s.unit_weight_n_m3 = 15.2e3;
    s.max_stress_a0 = 0.2;
    s.max_stress_a1 = 0.3;
    s.max_shear_deformation_m = 0.02;
    return s;
}

inline RunControl onThreads(int threads) {
    RunControl control;
    control.threads = threads;
    return control;
}

inline wheel::WheelParameters wheelA() { return {"wheel A", "Thesis Table 5.1", 0.092, 0.107}; }

// The model at one point straight from the contact API: the independent reference of the batch.
struct Reference {
    bool ok = false;
    double entry_angle_rad = 0.0;
    contact::WheelForces<double> forces;
};

inline Reference reference(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                           double slip, double slip_angle_rad, double load_n,
                           double entry_angle_rad = 0.0) {
    const contact::ContactParameters<double> p = contact::makeContactParameters(soil, wheel);
    Reference r;
    r.entry_angle_rad = entry_angle_rad;
    if (load_n > 0.0) {
        contact::EntryAngleProblem problem;
        problem.load_n = load_n;
        problem.slip = slip;
        problem.slip_angle_rad = slip_angle_rad;
        const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
        if (!solution.ok()) return r;
        r.entry_angle_rad = solution.entry_angle_rad;
    }
    r.forces =
        contact::computeForces(p, contact::OperatingPoint<double>{
                                      slip, slip_angle_rad, r.entry_angle_rad, 0.0, std::nullopt});
    r.ok = true;
    return r;
}

}  // namespace terra::gsa::testing
