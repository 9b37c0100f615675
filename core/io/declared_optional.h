#pragma once
/// @file declared_optional.h
/// Overrides in a declared field list (core/common/declared_fields.h): a member that is absent
/// unless the file gives it — std::optional of an enumeration, of a flag or of a whole number —
/// as a `fields::custom` kind read and written in the ObjectReader's words (an absent key leaves
/// the member empty; an empty member is not written). The rover's overrides of its scenario
/// (core/analysis/rover.h) are these.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/common/declared_fields.h"
#include "core/io/json_reader.h"

namespace terra::io {

/// An enumeration that may be absent: its names as fields::choice takes them (an alias is read,
/// never listed nor written); `allowed` lists them for the key table.
template <typename E>
auto optionalChoice(const char* key, std::optional<E>& value, std::vector<fields::Name<E>> names,
                    const char* allowed, const char* doc) {
    auto read = [names](ObjectReader& r, const char* k, std::optional<E>& out) {
        if (const nlohmann::json* v = r.has(k) ? r.value(k) : nullptr; v && v->is_string()) {
            for (const fields::Name<E>& n : names) {
                if (n.alias && v->get<std::string>() == n.name) {
                    out = n.value;
                    return;
                }
            }
        }
        const fields::Enum<E> e{k, nullptr, names, ""};
        std::string name;
        if (!r.choiceName(k, name, e.listed())) return;
        for (const fields::Name<E>& n : names) {
            if (name == n.name) out = n.value;
        }
    };
    auto write = [names](const std::optional<E>& v) {
        if (!v) return nlohmann::json();
        const fields::Enum<E> e{"", nullptr, names, ""};
        return nlohmann::json(e.nameOf(*v));
    };
    return fields::custom(key, value, "name", allowed, doc, std::move(read), std::move(write));
}

/// A flag that may be absent.
inline auto optionalFlag(const char* key, std::optional<bool>& value, const char* doc) {
    auto read = [](ObjectReader& r, const char* k, std::optional<bool>& out) {
        bool v = false;
        if (r.boolean(k, v)) out = v;
    };
    auto write = [](const std::optional<bool>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json();
    };
    return fields::custom(key, value, "true/false", "true, false", doc, read, write);
}

/// A whole number in [low, high] that may be absent; `allowed` says the range for the key table.
inline auto optionalInteger(const char* key, std::optional<int>& value, int low, int high,
                            const char* allowed, const char* doc) {
    auto read = [low, high](ObjectReader& r, const char* k, std::optional<int>& out) {
        int v = 0;
        if (r.integer(k, v, low, high)) out = v;
    };
    auto write = [](const std::optional<int>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json();
    };
    return fields::custom(key, value, "whole number", allowed, doc, read, write);
}

}  // namespace terra::io
