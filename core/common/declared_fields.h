#pragma once
/// @file declared_fields.h
/// Declared field lists: a settings struct lists each of its file keys once, in a member
///
///     template <typename Visitor>
///     void visitFields(Visitor& v) {
///         v(fields::number("noise_percent", noise_percent, {0.0, 100.0}, "%", "σ as % of …"));
///         v(fields::flag("refine", refine, "true: the full model"));
///     }
///
/// (Drake's `Serialize(Archive*)` with DRAKE_NVP, without the macros), and every generic tool
/// walks that list: the strict JSON reader and the writer (core/io/declared_json.h: an unknown
/// key gets "did you mean", a wrong kind or a value out of range is named with the field and
/// the allowed range, in the ObjectReader's one wording), the checks of a struct built in code
/// (the same reader run on its JSON) and the table of keys for the docs (describeFields below).
/// Adding a setting is one line in the list.
///
/// Kinds: a number (in the file's unit, with its range), a field of a field table (FieldInfo:
/// read in the user's unit, stored in SI), a whole number, a flag, an enumeration (its names,
/// with aliases read but never written), a string, a path (relative to the file that holds
/// it), a list of strings or of numbers, a nested object (a struct with its own list), the
/// members of a struct kept in the same object, and a custom kind (its own read and write, for
/// a key the kinds above cannot say). `std::optional<double>` members are numbers that may be
/// absent: toJson leaves them out when empty, as it leaves out empty lists and a number or
/// whole number at its `unset` value (the member's value meaning "none", never a file's).
///
/// This header knows no JSON (core/common is the bottom layer): the declarations hold
/// pointers to the members and what the readers need to check them.

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/common/field.h"
#include "core/common/range.h"

namespace terra::fields {

/// A number in the file's unit (stored as given): double, or std::optional<double> (absent
/// allowed, left out when empty).
template <typename T>
struct Number {
    const char* key;
    T* value;
    Range range;
    const char* unit;  ///< for the messages ("%", "N"); "" or "-" for a pure number
    const char* doc;
    std::optional<double> unset;  ///< the member's "none" (outside `range`): not written
};

/// A field of a field table (FieldInfo): the file holds the user's unit, the member SI.
template <typename T>
struct Scaled {
    const FieldInfo* info;
    T* si;                        ///< double or std::optional<double>
    std::optional<double> unset;  ///< the member's "none" in SI (outside the range): not written
};

/// A whole number in [low, high] (int or std::uint64_t).
template <typename T>
struct Integer {
    const char* key;
    T* value;
    T low;
    T high;
    const char* doc;
    std::optional<T> unset;  ///< the member's "none" (outside [low, high]): not written
};

/// A key whose value is read as it is: a flag, a string, a path, a list of strings, a nested
/// object (`Tag` tells a path from a string and marks an object).
template <typename T, typename Tag = void>
struct Plain {
    const char* key;
    T* value;
    const char* doc;
};
struct PathTag;
struct ObjectTag;

using Flag = Plain<bool>;
using Text = Plain<std::string>;
/// A file name: a relative one is read relative to the directory of the file that holds it.
using Path = Plain<std::string, PathTag>;
using Texts = Plain<std::vector<std::string>>;
/// A nested object: a struct with its own visitFields.
template <typename S>
using Object = Plain<S, ObjectTag>;

/// One name of an enumeration. An alias is read (an older or a second spelling) but neither
/// listed in the messages nor written.
template <typename E>
struct Name {
    const char* name;
    E value;
    bool alias = false;
};

template <typename E>
struct Enum {
    const char* key;
    E* value;
    std::vector<Name<E>> names;
    const char* doc;

    /// The listed names (the aliases left out).
    std::vector<std::string> listed() const {
        std::vector<std::string> out;
        for (const Name<E>& n : names) {
            if (!n.alias) out.emplace_back(n.name);
        }
        return out;
    }
    /// The name written for `v`: the first listed one.
    const char* nameOf(E v) const {
        for (const Name<E>& n : names) {
            if (!n.alias && n.value == v) return n.name;
        }
        return "";
    }
};

struct Numbers {
    const char* key;
    std::vector<double>* value;
    Range range;
    const char* unit;
    const char* doc;
    std::size_t min_count = 0;
    std::size_t max_count = 100000;
};

/// The fields of a member struct, in the same object as the enclosing struct's.
template <typename S>
struct Members {
    S* value;
};

/// A key that none of the kinds above says: `read(io::ObjectReader&, key, T&)` (reporting its
/// problems through the reader) and `write(const T&)` → JSON (null: the key is left out).
/// `kind` and `allowed` describe it for the docs.
template <typename T, typename Read, typename Write>
struct Custom {
    const char* key;
    T* value;
    const char* kind;
    const char* allowed;
    const char* doc;
    Read read;
    Write write;
};

// The declarations, one call per field.

template <typename T>
Number<T> number(const char* key, T& value, const Range& range, const char* unit, const char* doc,
                 std::optional<double> unset = std::nullopt) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>);
    return {key, &value, range, unit, doc, unset};
}
template <typename T>
Scaled<T> field(const FieldInfo& info, T& si, std::optional<double> unset = std::nullopt) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>);
    return {&info, &si, unset};
}
template <typename T>
Integer<T> integer(const char* key, T& value, std::type_identity_t<T> low,
                   std::type_identity_t<T> high, const char* doc,
                   std::optional<std::type_identity_t<T>> unset = std::nullopt) {
    static_assert(std::is_same_v<T, int> || std::is_same_v<T, std::uint64_t>);
    return {key, &value, low, high, doc, unset};
}
inline Flag flag(const char* key, bool& value, const char* doc) { return {key, &value, doc}; }
template <typename E>
Enum<E> choice(const char* key, E& value, std::initializer_list<Name<E>> names, const char* doc) {
    return {key, &value, std::vector<Name<E>>(names), doc};
}
inline Text text(const char* key, std::string& value, const char* doc) {
    return {key, &value, doc};
}
inline Path path(const char* key, std::string& value, const char* doc) {
    return {key, &value, doc};
}
inline Texts texts(const char* key, std::vector<std::string>& value, const char* doc) {
    return {key, &value, doc};
}
inline Numbers numbers(const char* key, std::vector<double>& value, const Range& range,
                       const char* unit, const char* doc, std::size_t min_count = 0,
                       std::size_t max_count = 100000) {
    return {key, &value, range, unit, doc, min_count, max_count};
}
template <typename S>
Object<S> object(const char* key, S& value, const char* doc) {
    return {key, &value, doc};
}
template <typename S>
Members<S> members(S& value) {
    return {&value};
}
template <typename T, typename Read, typename Write>
Custom<T, Read, Write> custom(const char* key, T& value, const char* kind, const char* allowed,
                              const char* doc, Read read, Write write) {
    return {key, &value, kind, allowed, doc, std::move(read), std::move(write)};
}

/// One row of a struct's key table (docs, --help): "noise.Fx_N", "number", "[0, 1e+06] N",
/// "0", "σ of F_x weighting the residuals".
struct FieldDoc {
    std::string key;
    std::string kind;           ///< number, whole number, true/false, name, string, path, …
    std::string allowed;        ///< range with unit, the names, or what a custom kind takes
    std::string default_value;  ///< of a default-constructed struct; "none" when unset
    std::string doc;
};

/// Collects FieldDocs (the visitor of describeFields).
class Describer {
public:
    explicit Describer(std::string prefix = {}) : prefix_(std::move(prefix)) {}

    template <typename T>
    void operator()(const Number<T>& f) {
        add(f.key, "number", withUnit(f.range.describe(), f.unit), numberText(*f.value, f.unset),
            f.doc);
    }
    template <typename T>
    void operator()(const Scaled<T>& f) {
        const std::optional<double> si = *f.si;
        const std::string value =
            si && !(f.unset && *si == *f.unset) ? formatNumber(f.info->toUser(*si)) : "none";
        add(f.info->key, "number",
            withUnit(f.info->range.describe(), f.info->displayUnit().c_str()), value,
            f.info->description);
    }
    template <typename T>
    void operator()(const Integer<T>& f) {
        const std::string value =
            f.unset && *f.value == *f.unset ? std::string("none") : std::to_string(*f.value);
        add(f.key, "whole number",
            "[" + std::to_string(f.low) + ", " + std::to_string(f.high) + "]", value, f.doc);
    }
    void operator()(const Flag& f) {
        add(f.key, "true/false", "true, false", *f.value ? "true" : "false", f.doc);
    }
    template <typename E>
    void operator()(const Enum<E>& f) {
        std::string names;
        for (const std::string& n : f.listed()) names += (names.empty() ? "" : ", ") + n;
        add(f.key, "name", names, f.nameOf(*f.value), f.doc);
    }
    void operator()(const Text& f) { add(f.key, "string", "", quoted(*f.value), f.doc); }
    void operator()(const Path& f) {
        add(f.key, "path", "relative to the file", quoted(*f.value), f.doc);
    }
    void operator()(const Texts& f) { add(f.key, "list of strings", "", "[]", f.doc); }
    void operator()(const Numbers& f) {
        add(f.key, "list of numbers", withUnit(f.range.describe(), f.unit), "[]", f.doc);
    }
    template <typename S>
    void operator()(const Object<S>& f) {
        add(f.key, "object", "", "", f.doc);
        Describer inner(prefix_ + f.key + ".");
        f.value->visitFields(inner);
        for (FieldDoc& d : inner.docs_) docs_.push_back(std::move(d));
    }
    template <typename S>
    void operator()(const Members<S>& f) {
        f.value->visitFields(*this);
    }
    template <typename T, typename R, typename W>
    void operator()(const Custom<T, R, W>& f) {
        add(f.key, f.kind, f.allowed, "", f.doc);
    }

    std::vector<FieldDoc>& docs() { return docs_; }

private:
    static std::string withUnit(const std::string& range, const char* unit) {
        const std::string u = unit == nullptr ? "" : unit;
        return u.empty() || u == "-" ? range : range + " " + u;
    }
    static std::string numberText(const std::optional<double>& v,
                                  const std::optional<double>& unset) {
        if (!v || (unset && *v == *unset)) return "none";
        return formatNumber(*v);
    }
    static std::string quoted(const std::string& s) { return "\"" + s + "\""; }
    void add(const char* key, std::string kind, std::string allowed, std::string value,
             const char* doc) {
        docs_.push_back({prefix_ + key, std::move(kind), std::move(allowed), std::move(value),
                         doc == nullptr ? "" : doc});
    }

    std::string prefix_;
    std::vector<FieldDoc> docs_;
};

/// The key table of S, defaults from a default-constructed S.
template <typename S>
std::vector<FieldDoc> describeFields() {
    S s{};
    Describer d;
    s.visitFields(d);
    return std::move(d.docs());
}

}  // namespace terra::fields
