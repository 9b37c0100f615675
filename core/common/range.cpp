#include "core/common/range.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace terra {

bool Range::contains(double value) const {
    if (std::isnan(value)) return false;
    const bool above_low = low_open ? value > low : value >= low;
    const bool below_high = high_open ? value < high : value <= high;
    return above_low && below_high;
}

std::string Range::describe() const {
    return std::string(low_open ? "(" : "[") + formatNumber(low) + ", " + formatNumber(high) +
           (high_open ? ")" : "]");
}

std::string formatFixed(double value, int decimals) {
    if (!std::isfinite(value)) return "-";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    std::string text = buffer;
    if (text[0] == '-' && text.find_first_not_of("0.", 1) == std::string::npos) text.erase(0, 1);
    return text;
}

std::string formatNumber(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (value == 0.0) return "0";  // never "-0"
    char buffer[32];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
    return error == std::errc{} ? std::string(buffer, end) : std::to_string(value);
}

double roundSignificant(double value, int digits) {
    if (!std::isfinite(value) || value == 0.0) return value;
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    return std::strtod(buffer, nullptr);
}

bool checkRange(std::vector<Issue>& issues, const std::string& field, double value,
                const Range& range, const std::string& unit) {
    if (range.contains(value)) return true;
    const std::string suffix = unit.empty() ? "" : " " + unit;
    if (!std::isfinite(value)) {
        issues.push_back({field, formatNumber(value) + " is not a finite number; allowed range " +
                                     range.describe() + suffix});
    } else {
        issues.push_back({field, formatNumber(value) + " is outside the allowed range " +
                                     range.describe() + suffix});
    }
    return false;
}

}  // namespace terra
