#pragma once
/// @file signal.h
/// Inputs as functions of time: constant, step, pulse, ramp or a table (linear interpolation,
/// held constant outside). Values are in whatever unit the caller stores (the scenario keeps SI).

#include <vector>

namespace terra::scenario {

struct Signal {
    enum class Kind { kConstant, kStep, kPulse, kRamp, kTable };
    Kind kind = Kind::kConstant;
    double value = 0.0;           ///< constant; the value before the step/pulse/ramp
    double amplitude = 0.0;       ///< step, pulse, ramp: the change added to `value`
    double start_s = 0.0;         ///< step, pulse, ramp: when the change starts [s]
    double duration_s = 0.0;      ///< pulse: how long it lasts; ramp: how long it takes [s]
    std::vector<double> times_s;  ///< table: strictly increasing times [s]
    std::vector<double> values;   ///< table: values at those times

    static Signal constant(double v) {
        Signal s;
        s.value = v;
        return s;
    }

    /// The value at time t [s]. Step: value + amplitude for t ≥ start. Pulse: value + amplitude
    /// for start ≤ t < start + duration. Ramp: linear from value at start to value + amplitude at
    /// start + duration.
    double at(double t_s) const;
};

}  // namespace terra::scenario
