#pragma once
/// @file test_support.h
/// What many core tests share (one definition each, so the unity build's batches do not clash):
/// the shipped presets and sandy loam on wheel A, degrees, a substring test, the message of a
/// rejected argument and the check of a result's summary against its JSON.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/analysis/analysis.h"
#include "core/identification/parameters.h"
#include "core/io/parameters_json.h"

namespace terra::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;  ///< [rad/deg]
inline constexpr double kExact = 1e-12;                   ///< exact arithmetic up to rounding

/// The presets shipped in resources/ of this tree.
inline const io::PresetLocations kLocations{{TERRA_RESOURCE_DIR}};

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// The shipped sandy loam on the shipped wheel A, at the default operating conditions.
inline analysis::Inputs sandyLoamOnA() {
    analysis::Inputs in;
    in.soil = io::resolveSoil(kLocations, "sandy-loam").value();
    in.wheel = io::resolveWheel(kLocations, "A").value();
    return in;
}

/// The message of the std::invalid_argument that `f` throws, or "(no exception)".
inline std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no exception)";
}

// The decimals of a number printed as `text` ("5.656" → 3, "84.0" → 1, "6" → 0).
inline int printedDecimalsOf(const std::string& text) {
    const std::string number = text.substr(0, text.find(' '));
    const auto dot = number.find('.');
    if (dot == std::string::npos || number.find('e') != std::string::npos) return 0;
    return static_cast<int>(number.size() - dot - 1);
}

/// `text` with every word that is a key of the identified parameters' table ("c_kPa") replaced by
/// the field's symbol ("c"): how a summary words what the JSON says by key (parameter_text.h).
/// Written here word by word, not with the core's ParameterText.
inline std::string withParameterSymbols(const std::string& text) {
    const auto word = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    std::string out;
    for (std::size_t at = 0; at < text.size();) {
        if (!word(text[at])) {
            out += text[at++];
            continue;
        }
        std::size_t end = at;
        while (end < text.size() && word(text[end])) ++end;
        const std::string token = text.substr(at, end - at);
        const auto* field = identification::findParameterField(token);
        out += field ? std::string(field->symbol) : token;
        at = end;
    }
    return out;
}

// Every number a summary shows is its JSON's, at the pointer the row names, printed to its
// digits (the sinkage in mm, the largest relative error in %); every text row's is the JSON's
// text, a flag's with the parameters named by symbol where the JSON names them by key; every
// heading's pointer is an object of the JSON.
inline void expectSummaryIsTheJson(const analysis::Summary& summary, const nlohmann::json& j) {
    for (const analysis::SummaryRow& row : summary) {
        if (row.json.empty()) continue;
        const nlohmann::json::json_pointer at(row.json);
        ASSERT_TRUE(j.contains(at)) << row.label << " at " << row.json;
        const nlohmann::json& value = j.at(at);
        if (row.emphasis == analysis::SummaryRow::Emphasis::kHeading) {
            EXPECT_TRUE(value.is_object()) << row.json;
        } else if (value.is_string() && contains(row.json, "/flags/")) {
            EXPECT_EQ(row.value, withParameterSymbols(value.get<std::string>())) << row.json;
        } else if (value.is_string()) {
            EXPECT_EQ(row.value, value.get<std::string>()) << row.json;
        } else {
            ASSERT_TRUE(value.is_number()) << row.json;
            EXPECT_EQ(row.number, value.get<double>()) << row.label << " at " << row.json;
            // Shown in mm, %, cm, or degrees of a JSON angle in radians.
            const bool radians = row.unit == "deg" && row.json.ends_with("_rad");
            const double scale = row.unit == "mm"                      ? 1e3
                                 : row.unit == "%" || row.unit == "cm" ? 100.0
                                 : radians                             ? 180.0 / std::numbers::pi
                                                                       : 1.0;
            const double shown = std::stod(row.value);
            const double printed = std::pow(10.0, -printedDecimalsOf(row.value));
            // Fixed decimals, or 3 to 6 significant digits.
            double tolerance = std::max(0.5 * printed, 5e-3 * std::abs(row.number * scale));
            // A value with its std is shown to the std's second digit ("800 ± 4200": hundreds,
            // formatAtStd): within half that place.
            const std::size_t pm = row.value.find(" ± ");
            if (pm != std::string::npos) {
                const double sd = std::stod(row.value.substr(pm + std::string(" ± ").size()));
                tolerance =
                    std::max(tolerance, 0.5 * std::pow(10.0, std::floor(std::log10(sd)) - 1));
            }
            EXPECT_NEAR(shown, row.number * scale, tolerance) << row.label << ": " << row.value;
        }
    }
}

}  // namespace terra::testing
