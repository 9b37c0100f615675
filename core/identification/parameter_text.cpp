#include "core/identification/parameter_text.h"

#include <algorithm>

#include "core/identification/parameters.h"

namespace terra::identification {
namespace {

// Calls `reference(key)` for each "{KEY}" of `text` whose KEY names a parameter of the table
// (an old key too) and `plain(part)` for the text between; a brace that opens no reference is
// plain text.
template <typename Reference, typename Plain>
void scan(const std::string& text, Reference reference, Plain plain) {
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t open = text.find('{', at);
        const std::size_t close = open == std::string::npos ? open : text.find('}', open);
        if (close == std::string::npos) break;
        const std::string_view key(text.data() + open + 1, close - open - 1);
        if (!lookupParameter(key)) {
            plain(std::string_view(text).substr(at, open + 1 - at));
            at = open + 1;
            continue;
        }
        plain(std::string_view(text).substr(at, open - at));
        reference(key);
        at = close + 1;
    }
    plain(std::string_view(text).substr(std::min(at, text.size())));
}

}  // namespace

std::string ParameterText::reference(std::string_view key) {
    // Appended, not "{" + key + "}": GCC 12 at -O3 warns of a bound it cannot prove (a false
    // -Wstringop-overflow inside char_traits).
    std::string text;
    text.reserve(key.size() + 2);
    text.push_back('{');
    text.append(key);
    text.push_back('}');
    return text;
}

std::string ParameterText::worded(ParameterNaming naming) const {
    std::string out;
    scan(
        text,
        [&](std::string_view key) {
            const ParameterField& field = *lookupParameter(key).field;
            out += naming == ParameterNaming::kSymbol ? field.symbol : field.key;
        },
        [&](std::string_view part) { out += part; });
    return out;
}

std::vector<std::string> ParameterText::parameters() const {
    std::vector<std::string> keys;
    scan(
        text,
        [&](std::string_view key) {
            const std::string name = lookupParameter(key).field->key;
            if (std::find(keys.begin(), keys.end(), name) == keys.end()) keys.push_back(name);
        },
        [](std::string_view) {});
    return keys;
}

std::vector<std::string> worded(const std::vector<ParameterText>& texts, ParameterNaming naming) {
    std::vector<std::string> out;
    out.reserve(texts.size());
    for (const ParameterText& text : texts) out.push_back(text.worded(naming));
    return out;
}

std::string solverOutcome(const std::string& termination) {
    const auto has = [&termination](const char* text) {
        return termination.find(text) != std::string::npos;
    };
    const auto starts = [&termination](const char* kind) {
        return termination.rfind(kind, 0) == 0;
    };
    if (starts("CONVERGENCE")) {
        if (has("every parameter is held")) return "nothing to fit (every parameter is held)";
        if (has("Gradient tolerance")) return "converged (the slope vanished at the minimum)";
        if (has("Parameter tolerance")) return "converged (the parameters stopped moving)";
        if (has("Function tolerance")) return "converged (the fit stopped improving)";
        return "converged";
    }
    if (starts("NO_CONVERGENCE"))
        return "stopped at its iteration limit before converging (usable; check the errors)";
    if (starts("STOPPED")) return "stopped in the basin of a minimum found before";
    if (starts("USER_SUCCESS")) {
        return "stopped when a parameter reached its bound, with no iterations left for a last "
               "pass (usable; check the errors)";
    }
    if (starts("USER_")) return "stopped by the caller";
    if (starts("FAILURE")) {
        return has("cannot be evaluated") ? "failed: the model cannot be evaluated at the solution"
                                          : "the solver failed";
    }
    return termination;
}

std::optional<bool> solverConverged(const std::string& termination) {
    if (termination.starts_with("CONVERGENCE")) return true;
    for (const char* kind : {"NO_CONVERGENCE", "STOPPED", "USER_", "FAILURE"}) {
        if (termination.starts_with(kind)) return false;
    }
    return std::nullopt;
}

}  // namespace terra::identification
