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
#include <type_traits>
#include <utility>
#include <vector>

#include "core/common/issue.h"
#include "core/common/table.h"

namespace terra::project::saved {

/// A number as JSON: itself when finite, null for NaN, "inf" / "-inf" for the infinities (an
/// identified soil without a shear limit has j_max = +inf, which must read back as +inf).
nlohmann::json number(double v);
/// The number `number` wrote; throws for anything else (a string other than "inf"/"-inf").
double numberOf(const nlohmann::json& v);
/// `json.at(key)` read by numberOf.
double numberAt(const nlohmann::json& json, const char* key);

nlohmann::json tableJson(const Table& table);
Table tableFrom(const nlohmann::json& json);

nlohmann::json matrixJson(const Eigen::MatrixXd& m);
Eigen::MatrixXd matrixFrom(const nlohmann::json& json);
nlohmann::json vectorJson(const Eigen::VectorXd& v);
Eigen::VectorXd vectorFrom(const nlohmann::json& json);

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

namespace terra::project::saved {

/// One key list per saved struct, read and written by the same list (as a declared field list,
/// core/common/declared_fields.h, for results: no ranges, NaN and the infinities kept by
/// `number`): specialise
///
///     template <> struct Fields<analysis::StressResult> {
///         template <typename V>
///         static void visit(V& v, analysis::StressResult& r) {
///             v("table", r.table);
///             v("entry_angle_deg", r.entry_angle_deg);
///         }
///     };
///
/// and fieldsJson(r) writes the object, fieldsFrom<S>(json) reads it back (every key required;
/// a missing key or a value of the wrong kind throws std::invalid_argument naming the key path,
/// "passes: 2: forces: fx: \"x\" is not a number"). A key that files written before it lack is
/// listed as `v("key", member, saved::kSince)`: absent, the member keeps its default.
template <typename S>
struct Fields;

/// A key that came after the first files of its struct: a file without it still reads.
enum class Presence { kRequired, kSince };
inline constexpr Presence kSince = Presence::kSince;

/// The last value of an enumeration saved as its number (specialise for each one saved): a
/// number outside [0, last] is refused.
template <typename E>
struct EnumLast;

/// A struct saved compactly, as the list of its Fields' values in their order ([n, sweeps, k, F,
/// share, p] for a trend test) rather than an object: specialise as std::true_type next to its
/// Fields. The keys then only name a wrong value in messages; every value is required (kSince
/// has no meaning there: a compact form that grows is a new form).
template <typename S>
struct Compact : std::false_type {};

/// How one member is saved: numbers by `number`, tables by tableJson, lists and optionals of
/// any of these, enumerations as their number, and structs by their Fields. Specialise for a
/// type that has its own JSON form (a soil profile).
template <typename T, typename = void>
struct Value {
    static nlohmann::json write(const T& value);
    static void read(const nlohmann::json& json, T& value);
};

class FieldsWriter {
public:
    explicit FieldsWriter(nlohmann::json& out) : out_(&out) {}
    template <typename T>
    void operator()(const char* key, const T& value, Presence = Presence::kRequired) {
        (*out_)[key] = Value<T>::write(value);
    }

private:
    nlohmann::json* out_;
};

class FieldsReader {
public:
    explicit FieldsReader(const nlohmann::json& in) : in_(&in) {}
    template <typename T>
    void operator()(const char* key, T& value, Presence presence = Presence::kRequired) {
        if (presence == Presence::kSince && !in_->contains(key)) return;
        readKey(*in_, key, [&value](const nlohmann::json& j) {
            Value<T>::read(j, value);
            return 0;
        });
    }

private:
    const nlohmann::json* in_;
};

/// Compact structs: the values in order, and back (the count checked).
class PositionalWriter {
public:
    explicit PositionalWriter(nlohmann::json& out) : out_(&out) {}
    template <typename T>
    void operator()(const char*, const T& value, Presence = Presence::kRequired) {
        out_->push_back(Value<T>::write(value));
    }

private:
    nlohmann::json* out_;
};

class PositionalReader {
public:
    explicit PositionalReader(const nlohmann::json& in) : in_(&in) {}
    template <typename T>
    void operator()(const char* key, T& value, Presence = Presence::kRequired) {
        try {
            Value<T>::read(in_->at(next_++), value);
        } catch (const std::exception& e) {
            throw std::invalid_argument(std::string(key) + ": " + e.what());
        }
    }

private:
    const nlohmann::json* in_;
    std::size_t next_ = 0;
};

template <typename S>
nlohmann::json fieldsJson(const S& s) {
    if constexpr (Compact<S>::value) {
        nlohmann::json out = nlohmann::json::array();
        PositionalWriter w(out);
        Fields<S>::visit(w, const_cast<S&>(s));
        return out;
    } else {
        nlohmann::json out = nlohmann::json::object();
        FieldsWriter w(out);
        // One list for reading and writing: writing changes nothing.
        Fields<S>::visit(w, const_cast<S&>(s));
        return out;
    }
}

template <typename S>
S fieldsFrom(const nlohmann::json& json) {
    S s{};
    if constexpr (Compact<S>::value) {
        std::size_t count = 0;
        auto counter = [&count](const char*, auto&&...) { ++count; };
        Fields<S>::visit(counter, s);
        if (!json.is_array() || json.size() != count)
            throw std::invalid_argument(json.dump() + ": expected a list of " +
                                        std::to_string(count) + " values");
        PositionalReader r(json);
        Fields<S>::visit(r, s);
    } else {
        if (!json.is_object()) throw std::invalid_argument(json.dump() + " is not an object");
        FieldsReader r(json);
        Fields<S>::visit(r, s);
    }
    return s;
}

namespace detail {
template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};
template <typename T>
struct IsOptional : std::false_type {};
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};
template <typename T>
struct IsArray : std::false_type {};
template <typename T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};
template <typename T>
struct IsPair : std::false_type {};
template <typename A, typename B>
struct IsPair<std::pair<A, B>> : std::true_type {};
}  // namespace detail

template <typename T, typename Enable>
nlohmann::json Value<T, Enable>::write(const T& value) {
    if constexpr (std::is_same_v<T, double>) {
        return number(value);
    } else if constexpr (std::is_same_v<T, bool> || std::is_integral_v<T> ||
                         std::is_same_v<T, std::string>) {
        return value;
    } else if constexpr (std::is_enum_v<T>) {
        return static_cast<int>(value);
    } else if constexpr (std::is_same_v<T, Table>) {
        return tableJson(value);
    } else if constexpr (detail::IsOptional<T>::value) {
        return value ? Value<typename T::value_type>::write(*value) : nlohmann::json(nullptr);
    } else if constexpr (detail::IsPair<T>::value) {  // [first, second]
        return nlohmann::json::array({Value<typename T::first_type>::write(value.first),
                                      Value<typename T::second_type>::write(value.second)});
    } else if constexpr (detail::IsVector<T>::value || detail::IsArray<T>::value) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& item : value)
            out.push_back(Value<std::decay_t<decltype(item)>>::write(item));
        return out;
    } else {
        return fieldsJson(value);
    }
}

template <typename T, typename Enable>
void Value<T, Enable>::read(const nlohmann::json& json, T& value) {
    if constexpr (std::is_same_v<T, double>) {
        value = numberOf(json);
    } else if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>) {
        value = json.get<T>();
    } else if constexpr (std::is_integral_v<T>) {
        if (!json.is_number_integer()) throw std::invalid_argument(json.dump() + " is not whole");
        value = json.get<T>();
    } else if constexpr (std::is_enum_v<T>) {
        const int v = json.is_number_integer() ? json.get<int>() : -1;
        if (v < 0 || v > static_cast<int>(EnumLast<T>::value))
            throw std::invalid_argument(json.dump() + " is not a known value");
        value = static_cast<T>(v);
    } else if constexpr (std::is_same_v<T, Table>) {
        value = tableFrom(json);
    } else if constexpr (detail::IsOptional<T>::value) {
        if (json.is_null()) {
            value.reset();
        } else {
            typename T::value_type inner{};
            Value<typename T::value_type>::read(json, inner);
            value = std::move(inner);
        }
    } else if constexpr (detail::IsPair<T>::value) {
        if (!json.is_array() || json.size() != 2)
            throw std::invalid_argument(json.dump() + " is not a pair");
        Value<typename T::first_type>::read(json[0], value.first);
        Value<typename T::second_type>::read(json[1], value.second);
    } else if constexpr (detail::IsVector<T>::value) {
        if (!json.is_array()) throw std::invalid_argument(json.dump() + " is not a list");
        value.clear();
        for (std::size_t i = 0; i < json.size(); ++i) {
            typename T::value_type item{};
            try {
                Value<typename T::value_type>::read(json[i], item);
            } catch (const std::exception& e) {
                throw std::invalid_argument(std::to_string(i) + ": " + e.what());
            }
            value.push_back(std::move(item));
        }
    } else if constexpr (detail::IsArray<T>::value) {
        if (!json.is_array() || json.size() != value.size())
            throw std::invalid_argument("expected " + std::to_string(value.size()) + " values");
        for (std::size_t i = 0; i < value.size(); ++i)
            Value<typename T::value_type>::read(json[i], value[i]);
    } else {
        value = fieldsFrom<T>(json);
    }
}

/// An issue as [where, message] (a data file's skipped rows, a fit's issues).
template <>
struct Compact<Issue> : std::true_type {};
template <>
struct Fields<Issue> {
    template <typename V>
    static void visit(V& v, Issue& i) {
        v("where", i.where);
        v("message", i.message);
    }
};

}  // namespace terra::project::saved
