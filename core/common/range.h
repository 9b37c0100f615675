#pragma once
/// @file range.h
/// Allowed ranges of user-facing fields, checked the same way everywhere so that every error names
/// the field, the value and the range ("phi_deg = 75 is outside the allowed range [0, 60)").

#include <string>
#include <vector>

#include "core/common/issue.h"

namespace terra {

/// A closed or half-open interval of allowed values, in the units the user sees.
struct Range {
    double low;
    double high;
    bool low_open = false;   ///< true: `low` itself is not allowed
    bool high_open = false;  ///< true: `high` itself is not allowed

    bool contains(double value) const;
    std::string describe() const;  ///< "[0, 60)"
};

/// Formats a number for messages: shortest round-trip text ("0.025", "1e-06", "nan").
std::string formatNumber(double value);

/// Fixed-point text with `decimals` decimals for tables and summaries ("5.656"); never "-0.000"
/// (a negative zero or a tiny negative value that rounds to zero gives "0.000"); "-" for NaN or
/// an infinity.
std::string formatFixed(double value, int decimals);

/// A standard deviation as tables and summaries show it: rounded to the place of its second
/// significant digit ("0.84", "0.0012", "20"); "" when there is none (≤ 0 or not finite).
std::string formatStd(double std);

/// An estimate to the decimal place its std supports, the place formatStd shows (28.8312 with a
/// std of 0.84 → "28.83"): the digits beyond it are noise. When that place would need more than
/// six significant digits (1.5e6 ± 20), six; without a std (formatStd ""), formatNumber.
std::string formatAtStd(double value, double std);

/// `value` rounded to `digits` significant decimal digits: unit conversions at the edges (rad→deg)
/// then give back the number the user typed (29, not 29.000000000000004).
double roundSignificant(double value, int digits = 12);

/// An angle in radians as the edges write it in degrees: radToDeg, then roundSignificant (an
/// input of 15° is written 15 again).
double roundedDegrees(double rad);

/// Appends an issue when `value` is NaN, infinite or outside `range`; returns whether it was fine.
bool checkRange(std::vector<Issue>& issues, const std::string& field, double value,
                const Range& range, const std::string& unit = {});

}  // namespace terra
