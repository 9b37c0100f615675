#pragma once
/// @file declared_json.h
/// The JSON reader and writer of a struct with a declared field list (core/common/
/// declared_fields.h): `readFields(reader, s)` reads every declared key strictly with the
/// ObjectReader (its wording: wrong kinds and values out of range named with the field and the
/// allowed range; the caller's finish() gives unknown keys their "did you mean"), `fieldsToJson(s)`
/// writes them back (a value read from it reads the same), and `fieldIssues(s)` checks a struct
/// built in code against the same list, in the same words.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/common/declared_fields.h"
#include "core/io/json_reader.h"

namespace terra::io {

/// Reads declared fields through an ObjectReader. A key absent from the object leaves its member
/// at its value (the struct's default); `base_dir` resolves relative paths (empty: kept as given).
class FieldReader {
public:
    FieldReader(ObjectReader& reader, std::filesystem::path base_dir = {})
        : r_(&reader), base_dir_(std::move(base_dir)) {}

    void operator()(const fields::Number<double>& f) {
        r_->number(f.key, *f.value, f.range, unitOf(f.unit));
    }
    void operator()(const fields::Number<std::optional<double>>& f) {
        double v = 0.0;
        if (r_->number(f.key, v, f.range, unitOf(f.unit))) *f.value = v;
    }
    void operator()(const fields::Scaled<double>& f) { r_->field(*f.info, *f.si); }
    void operator()(const fields::Scaled<std::optional<double>>& f) {
        double v = 0.0;
        if (r_->field(*f.info, v)) *f.si = v;
    }
    template <typename T>
    void operator()(const fields::Integer<T>& f) {
        r_->integer(f.key, *f.value, f.low, f.high);
    }
    void operator()(const fields::Flag& f) { r_->boolean(f.key, *f.value); }
    template <typename E>
    void operator()(const fields::Enum<E>& f) {
        // An alias is taken as it is; any other name is checked against the listed ones.
        if (const nlohmann::json* v = r_->has(f.key) ? r_->value(f.key) : nullptr;
            v != nullptr && v->is_string()) {
            for (const fields::Name<E>& n : f.names) {
                if (n.alias && v->get<std::string>() == n.name) {
                    *f.value = n.value;
                    return;
                }
            }
        }
        std::string name;
        if (!r_->choiceName(f.key, name, f.listed())) return;
        for (const fields::Name<E>& n : f.names) {
            if (name == n.name) *f.value = n.value;
        }
    }
    void operator()(const fields::Text& f) { r_->text(f.key, *f.value); }
    void operator()(const fields::Path& f) {
        if (!r_->text(f.key, *f.value) || f.value->empty() || base_dir_.empty()) return;
        const std::filesystem::path p(*f.value);
        if (p.is_relative()) *f.value = (base_dir_ / p).string();
    }
    void operator()(const fields::Texts& f) { r_->texts(f.key, *f.value); }
    void operator()(const fields::Numbers& f) {
        r_->numbers(f.key, *f.value, f.range, unitOf(f.unit), f.min_count, f.max_count);
    }
    template <typename S>
    void operator()(const fields::Object<S>& f) {
        if (!r_->has(f.key)) {
            r_->allow(f.key);
            return;
        }
        ObjectReader inner = r_->object(f.key);
        FieldReader v(inner, base_dir_);
        f.value->visitFields(v);
        inner.finish();
    }
    template <typename S>
    void operator()(const fields::Members<S>& f) {
        f.value->visitFields(*this);
    }
    template <typename T, typename R, typename W>
    void operator()(const fields::Custom<T, R, W>& f) {
        f.read(*r_, f.key, *f.value);
    }

private:
    static std::string_view unitOf(const char* unit) { return unit == nullptr ? "" : unit; }

    ObjectReader* r_;
    std::filesystem::path base_dir_;
};

/// Writes declared fields into a JSON object: numbers in the file's unit (a field table's in
/// its user unit), enumerations by their first listed name; an empty optional, an empty list, a
/// number at its `unset` value and a custom kind that writes null are left out.
class FieldWriter {
public:
    explicit FieldWriter(nlohmann::json& out) : out_(&out) {}

    void operator()(const fields::Number<double>& f) {
        if (!(f.unset && *f.value == *f.unset)) (*out_)[f.key] = *f.value;
    }
    void operator()(const fields::Number<std::optional<double>>& f) {
        if (*f.value) (*out_)[f.key] = **f.value;
    }
    void operator()(const fields::Scaled<double>& f) {
        if (!(f.unset && *f.si == *f.unset)) (*out_)[f.info->key] = f.info->toUser(*f.si);
    }
    void operator()(const fields::Scaled<std::optional<double>>& f) {
        if (*f.si && !(f.unset && **f.si == *f.unset))
            (*out_)[f.info->key] = f.info->toUser(**f.si);
    }
    template <typename T>
    void operator()(const fields::Integer<T>& f) {
        if (!(f.unset && *f.value == *f.unset)) (*out_)[f.key] = *f.value;
    }
    void operator()(const fields::Flag& f) { (*out_)[f.key] = *f.value; }
    template <typename E>
    void operator()(const fields::Enum<E>& f) {
        (*out_)[f.key] = f.nameOf(*f.value);
    }
    void operator()(const fields::Text& f) { (*out_)[f.key] = *f.value; }
    void operator()(const fields::Path& f) { (*out_)[f.key] = *f.value; }
    void operator()(const fields::Texts& f) {
        if (!f.value->empty()) (*out_)[f.key] = *f.value;
    }
    void operator()(const fields::Numbers& f) {
        if (!f.value->empty()) (*out_)[f.key] = *f.value;
    }
    template <typename S>
    void operator()(const fields::Object<S>& f) {
        nlohmann::json inner = nlohmann::json::object();
        FieldWriter v(inner);
        f.value->visitFields(v);
        (*out_)[f.key] = std::move(inner);
    }
    template <typename S>
    void operator()(const fields::Members<S>& f) {
        f.value->visitFields(*this);
    }
    template <typename T, typename R, typename W>
    void operator()(const fields::Custom<T, R, W>& f) {
        nlohmann::json j = f.write(*f.value);
        if (!j.is_null()) (*out_)[f.key] = std::move(j);
    }

private:
    nlohmann::json* out_;
};

/// Reads the declared fields of `s` from `r` (the caller calls r.finish(), after any keys of its
/// own). Relative paths are resolved against `base_dir` when it is not empty.
template <typename S>
void readFields(ObjectReader& r, S& s, const std::filesystem::path& base_dir = {}) {
    FieldReader v(r, base_dir);
    s.visitFields(v);
}

/// The declared fields of `s` as a JSON object.
template <typename S>
nlohmann::json fieldsToJson(const S& s) {
    nlohmann::json out = nlohmann::json::object();
    FieldWriter v(out);
    // The list is one member for reading and writing (as Drake's Serialize): writing changes
    // nothing.
    const_cast<S&>(s).visitFields(v);
    return out;
}

/// Every problem of a struct built in code (a panel's, a test's), as its reader words it: the
/// reader run on its JSON (issues located at the keys, "holdout: 1.5 is outside …").
template <typename S>
std::vector<Issue> fieldIssues(const S& s) {
    const nlohmann::json j = fieldsToJson(s);
    std::vector<Issue> issues;
    ObjectReader r(j, issues);
    S scratch{};
    readFields(r, scratch);
    r.finish();
    return issues;
}

}  // namespace terra::io
