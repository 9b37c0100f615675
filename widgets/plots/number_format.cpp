#include "widgets/plots/number_format.h"

#include <algorithm>
#include <cmath>

#include "core/common/range.h"

namespace terra::ui {
namespace {

/// Below this fraction of the scale a value is rounding noise (doubles carry ~16 digits; a
/// solver's or a sum's noise stays far below 1e-9 of the values it works with).
constexpr double kNoise = 1e-9;

/// The decimal exponent of the leading digit (0.0137 → -2, 73 → 1).
int leadingExponent(double value) {
    return static_cast<int>(std::floor(std::log10(std::abs(value))));
}

}  // namespace

QString formatStd(double std) {
    const std::string text = terra::formatStd(std);
    return text.empty() ? QString::fromUtf8("–") : QString::fromStdString(text);
}

QString formatWithStd(double value, double std) {
    if (!(std > 0.0) || !std::isfinite(std)) return formatNumber(value);
    if (!std::isfinite(value)) return QString::number(value);
    return QString::fromStdString(formatAtStd(value, std));  // the summaries' rule (core)
}

QString formatNumber(double value, double scale, int digits) {
    if (!std::isfinite(value)) return QString::number(value);
    if (value == 0.0 || std::abs(value) <= kNoise * std::abs(scale)) return "0";
    const double magnitude = std::abs(value);
    if (magnitude >= 1e-4 && magnitude < 1e6) {
        const int decimals = std::max(0, digits - 1 - leadingExponent(value));
        QString text = QString::number(value, 'f', decimals);
        // Trailing zeros after the point carry no information here ("0.5000" → "0.5").
        if (text.contains('.')) {
            while (text.endsWith('0')) text.chop(1);
            if (text.endsWith('.')) text.chop(1);
        }
        return text;
    }
    return QString::number(value, 'e', digits - 1);
}

}  // namespace terra::ui
