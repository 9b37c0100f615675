#include "core/common/field.h"

namespace terra {

std::string FieldInfo::displayUnit() const {
    const std::string u = unit;
    return u == "-" ? std::string() : u;
}

std::string FieldInfo::symbolWithUnit() const {
    const std::string u = displayUnit();
    return u.empty() ? std::string(symbol) : std::string(symbol) + " [" + u + "]";
}

Range FieldInfo::siRange() const {
    return {range.low * to_si, range.high * to_si, range.low_open, range.high_open};
}

double FieldInfo::toUser(double si) const {
    const double raw = si / to_si;
    for (int digits = 12; digits <= 17; ++digits) {
        const double candidate = roundSignificant(raw, digits);
        if (candidate * to_si == si) return candidate;
    }
    return raw;
}

}  // namespace terra
