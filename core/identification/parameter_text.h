#pragma once
/// @file parameter_text.h
/// A text that names identified parameters — the solver's advice ("K_s and n₀ trade off along a
/// flat valley …"), a step's name ("II: K_s, n₀, n₁ (Fz, Eq. 4.17)") — through the parameter table
/// (parameters.h) instead of spelling them, so that each renderer words the names as its reader
/// needs (issue 26): JSON and what the command line says of its inputs by the field's key
/// ("Ks_kPa", as `--prior` and `--fix` take it), a summary (printed by the command line and shown
/// by the studio) by the symbol ("K_s").
///
/// The text holds each parameter as "{KEY}" (the field's key in braces, `reference`), so that it
/// is one string that a saved result keeps as it is; a text saved before it named parameters so
/// has no reference and is worded as it was written.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace terra::identification {

/// How a parameter is named: by its key (what files, flags and JSON take: "Ks_kPa", "phi_deg") or
/// by its symbol (what a person reads: "K_s", "φ").
enum class ParameterNaming { kKey, kSymbol };

struct ParameterText {
    /// The text with "{KEY}" where a parameter is named ("{c_kPa} and {phi_deg} trade off …").
    std::string text;

    ParameterText() = default;
    /// A text (with or without references; a plain text names no parameter).
    ParameterText(std::string text) : text(std::move(text)) {}  // NOLINT(google-explicit-*)
    ParameterText(const char* text) : text(text) {}             // NOLINT(google-explicit-*)

    /// "{KEY}": how a text refers to the parameter with this key.
    static std::string reference(std::string_view key);

    /// The text with every reference replaced by the parameter's key or symbol; a reference to
    /// no parameter of the table is left as its key.
    std::string worded(ParameterNaming naming) const;
    /// The keys the text refers to, in order of first appearance.
    std::vector<std::string> parameters() const;

    bool operator==(const ParameterText& other) const = default;
};

/// Each text worded (ParameterText::worded).
std::vector<std::string> worded(const std::vector<ParameterText>& texts, ParameterNaming naming);

/// A termination in a user's words (issue 27: no optimizer wording on screen): Ceres'
/// "CONVERGENCE: Function tolerance reached. |cost_change|/cost: 1.2e-07 <= 1e-06" is "converged
/// (the fit stopped improving)", NO_CONVERGENCE, FAILURE and STOPPED (box_solver.h) likewise,
/// USER_SUCCESS (the box solver's bound watch ended the last pass the budget allowed) and another
/// USER_ (a caller's stop); a text that is not a solver's termination (a step's own note) is
/// returned as it is.
std::string solverOutcome(const std::string& termination);
/// Whether a solver's termination is a convergence (CONVERGENCE) or not (NO_CONVERGENCE, STOPPED,
/// USER_, FAILURE); none for a text that is not a solver's termination (a step's own note).
std::optional<bool> solverConverged(const std::string& termination);

}  // namespace terra::identification
