#pragma once
/// @file result_json.h
/// The pieces every saved result is written with (core/project/results.h and the per-analysis
/// saved_*.h): numbers that survive JSON (which has no NaN or infinity), tables, Eigen matrices
/// and fixed-size arrays. The readers are strict: a missing key, a value of the wrong type or a
/// row of the wrong length throws std::invalid_argument (or nlohmann's type error) with what is
/// wrong; the callers turn it into an Issue under the section's name.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/table.h"

namespace terra::project::saved {

/// A number as JSON: itself when finite, null for NaN, "inf" / "-inf" for the infinities (an
/// identified soil without a shear limit has j_max = +inf, which must read back as +inf).
nlohmann::json number(double v);
/// The number `number` wrote; throws for anything else (a string other than "inf"/"-inf").
double numberOf(const nlohmann::json& v);
/// `json.at(key)` read by numberOf.
double numberAt(const nlohmann::json& json, const char* key);

nlohmann::json optionalJson(const std::optional<double>& v);  ///< null when empty
/// Absent or null: empty (an optional NaN is not written: `number` of NaN is null too).
std::optional<double> optionalAt(const nlohmann::json& json, const char* key);

nlohmann::json tableJson(const Table& table);
Table tableFrom(const nlohmann::json& json);

nlohmann::json matrixJson(const Eigen::MatrixXd& m);
Eigen::MatrixXd matrixFrom(const nlohmann::json& json);
nlohmann::json vectorJson(const Eigen::VectorXd& v);
Eigen::VectorXd vectorFrom(const nlohmann::json& json);

template <std::size_t N>
nlohmann::json arrayJson(const std::array<double, N>& values) {
    nlohmann::json out = nlohmann::json::array();
    for (double v : values) out.push_back(number(v));
    return out;
}

/// Exactly N numbers; throws for another count.
template <std::size_t N>
std::array<double, N> arrayFrom(const nlohmann::json& json) {
    if (!json.is_array() || json.size() != N)
        throw std::invalid_argument("expected " + std::to_string(N) + " numbers");
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = numberOf(json[i]);
    return out;
}

/// Exactly N booleans; throws for another count.
template <std::size_t N>
std::array<bool, N> flagsFrom(const nlohmann::json& json) {
    if (!json.is_array() || json.size() != N)
        throw std::invalid_argument("expected " + std::to_string(N) + " booleans");
    std::array<bool, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = json[i].get<bool>();
    return out;
}

/// `f(json.at(key))`, the key named in the message of what it throws ("summary: x_m: …").
template <typename F>
auto readKey(const nlohmann::json& json, const char* key, F f) {
    try {
        return f(json.at(key));
    } catch (const std::exception& e) {
        throw std::invalid_argument(std::string(key) + ": " + e.what());
    }
}

}  // namespace terra::project::saved
