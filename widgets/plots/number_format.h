#pragma once
/// @file number_format.h
/// Numbers for people, with the digits their uncertainty or their size supports: a fitted value
/// to the decimal place of its std ("28.83 ± 0.84", not "28.829 ± 0.841"; "0.0023 ± 0.0011", not
/// "0.00"), and rounding noise of a computation as 0 (no "c = −1.25e-18 kPa", no "4.945e-15 mm").
/// Used by the identification panel and the calibration dialog.

#include <QString>

namespace terra::ui {

/// A standard deviation to two significant digits ("0.84", "73", "0.0011"); "–" when it is not a
/// positive finite number.
QString formatStd(double std);

/// `value` to the decimal place of its std's second significant digit ("28.83" for 28.829 ± 0.84,
/// "1611" for 1610.8 ± 73, "0.0023" for 0.0023 ± 0.0011); "0" when it rounds to zero there (never
/// "-0"). Without a usable std (0, negative, not finite): formatNumber(value).
QString formatWithStd(double value, double std);

/// `value` to `digits` significant digits, plain between 1e-4 and 1e6 and in e-notation outside;
/// "0" when |value| ≤ 1e-9 |scale|, rounding noise next to the values of size `scale` it came
/// with (a parameter's range, the largest error of a table row).
QString formatNumber(double value, double scale = 0.0, int digits = 4);

}  // namespace terra::ui
