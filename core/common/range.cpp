#include "core/common/range.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/common/units.h"

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

namespace {

// The decimal exponent of the leading digit (0.0137 → -2, 73 → 1).
int leadingExponent(double value) {
    return static_cast<int>(std::floor(std::log10(std::abs(value))));
}

// `value` rounded to 10^`exponent` in plain notation (decimals only below 10^0); "0", never "-0".
std::string atPlace(double value, int exponent) {
    const double unit = std::pow(10.0, exponent);
    const double rounded = std::round(value / unit) * unit;
    if (rounded == 0.0) return "0";
    return formatFixed(rounded, std::max(0, -exponent));
}

// `digits` significant digits, plain from 1e-4 to 1e6 without trailing zeros, else scientific.
std::string significant(double value, int digits) {
    const double magnitude = std::abs(value);
    if (magnitude >= 1e-4 && magnitude < 1e6) {
        std::string text = formatFixed(value, std::max(0, digits - 1 - leadingExponent(value)));
        if (text.find('.') != std::string::npos) {
            while (text.back() == '0') text.pop_back();
            if (text.back() == '.') text.pop_back();
        }
        return text;
    }
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, value);
    return buffer;
}

}  // namespace

std::string formatStd(double std) {
    if (!(std > 0.0) || !std::isfinite(std)) return {};
    return atPlace(std, leadingExponent(std) - 1);
}

std::string formatAtStd(double value, double std) {
    if (!(std > 0.0) || !std::isfinite(std)) return formatNumber(value);
    if (!std::isfinite(value)) return formatNumber(value);
    const int place = leadingExponent(std) - 1;
    if (value != 0.0 && leadingExponent(value) - place > 6) return significant(value, 6);
    return atPlace(value, place);
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

double roundedDegrees(double rad) { return roundSignificant(units::radToDeg(rad)); }

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
