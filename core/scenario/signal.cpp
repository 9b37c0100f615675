#include "core/scenario/signal.h"

#include <algorithm>

namespace terra::scenario {

double Signal::at(double t) const {
    switch (kind) {
        case Kind::kConstant:
            return value;
        case Kind::kStep:
            return t >= start_s ? value + amplitude : value;
        case Kind::kPulse:
            return t >= start_s && t < start_s + duration_s ? value + amplitude : value;
        case Kind::kRamp: {
            if (t <= start_s) return value;
            if (duration_s <= 0.0 || t >= start_s + duration_s) return value + amplitude;
            return value + amplitude * (t - start_s) / duration_s;
        }
        case Kind::kTable: {
            if (times_s.empty()) return 0.0;
            if (t <= times_s.front()) return values.front();
            if (t >= times_s.back()) return values.back();
            const auto it = std::upper_bound(times_s.begin(), times_s.end(), t);
            const std::size_t i = static_cast<std::size_t>(it - times_s.begin());
            const double f = (t - times_s[i - 1]) / (times_s[i] - times_s[i - 1]);
            return values[i - 1] + f * (values[i] - values[i - 1]);
        }
    }
    return value;
}

}  // namespace terra::scenario
