#include "core/analysis/identification.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/analysis/global_sensitivity.h"
#include "core/analysis/registry.h"
#include "core/analysis/sweep.h"
#include "core/common/quoted.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/contact/wheel_forces.h"
#include "core/identification/parameter_text.h"
#include "core/identification/synthetic.h"
#include "core/io/declared_json.h"
#include "core/io/parameters_json.h"

namespace terra::analysis {
namespace {

namespace id = identification;

// A measured value, or NaN when the data set does not carry the channel.
double measuredOr(bool measured, double value) {
    return measured ? value : std::numeric_limits<double>::quiet_NaN();
}

// The data of the settings: given, read from the CSV, or synthesised from the inputs' soil.
// The full model reads data without an entry angle (θ_f from the load) and with any channels.
id::ColumnNeeds needsOf(const IdentificationSettings& s) {
    return s.refine ? id::ColumnNeeds::kFullModel : id::ColumnNeeds::kDecoupled;
}

void loadData(const Inputs& in, const IdentificationSettings& s, IdentificationResult& out) {
    if (s.data) {
        out.data = *s.data;
        out.warnings = s.data_warnings;
        return;
    }
    if (!s.csv.empty()) {
        auto read = id::readDataSet(
            s.csv, s.skip_bad_rows ? id::BadRows::kSkip : id::BadRows::kStop, needsOf(s));
        if (!read) {
            out.status = Outcome::Status::kInvalidInput;
            out.data_issues = read.issues();
            out.message = read.message();
            return;
        }
        out.data = read->data;
        out.skipped = read->skipped;
        for (const Issue& issue : read->warnings)
            out.warnings.push_back(issue.where + ": " + issue.message);
        return;
    }
    id::SyntheticSpec spec;
    spec.loads_n = s.synthetic.loads_n.empty() ? std::vector<double>{in.conditions.load_n}
                                               : s.synthetic.loads_n;
    spec.slips = linspace(0.0, std::min(in.conditions.slip_max, SyntheticSource::kMaxSlip),
                          s.synthetic.slip_count);
    const double relative = s.synthetic.noise_percent / 100.0;
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = relative;
    spec.seed = s.synthetic.seed;
    id::SyntheticData synthetic = id::synthesize(in.contact(), spec);
    out.data = std::move(synthetic.data);
    out.warnings = std::move(synthetic.warnings);
}

}  // namespace

void readFixedParameters(io::ObjectReader& r, const char* key,
                         std::vector<std::pair<std::string, double>>& out) {
    if (!r.has(key)) {
        r.allow(key);
        return;
    }
    io::ObjectReader fix = r.object(key);
    for (const IdentifiedField& field : identifiedFields()) {
        if (!fullParameterOf(field)) continue;  // n1 is not refined
        double value = 0.0;
        if (fix.number(field.key, value, field.range, field.displayUnit()))
            out.emplace_back(field.key, value);
        // An old key ("Ks", "n") is read as the field's, stored under the field's key
        // (readIdentificationSettings notes the deprecation).
        for (const id::DeprecatedParameterKey& old : id::deprecatedParameterKeys()) {
            if (field.key != std::string_view(old.key) || !fix.has(old.old_key)) continue;
            if (fix.has(field.key)) {
                fix.report(old.old_key, "the same parameter as '" + std::string(field.key) +
                                            "' (its deprecated key): give one");
                fix.allow(old.old_key);
            } else if (fix.number(old.old_key, value, field.range, field.displayUnit())) {
                out.emplace_back(field.key, value);
            }
        }
    }
    fix.finish();
}

nlohmann::json fixedParametersJson(const std::vector<std::pair<std::string, double>>& fixed) {
    if (fixed.empty()) return nullptr;
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : fixed) out[key] = value;
    return out;
}

std::vector<Issue> identificationRuleIssues(const IdentificationSettings& s) {
    std::vector<Issue> issues;
    if (s.fit_max_shear_deformation && s.max_shear_deformation_m)
        issues.push_back({"fit_jmax", "give jmax_m (held) or fit_jmax (identified), not both"});
    if (s.holdout_fraction != 0.0 && s.folds != 0)
        issues.push_back({"holdout", "give a holdout fraction or folds, not both"});
    return issues;
}

std::vector<Issue> deprecatedPriorItems(const IdentificationSettings& s) {
    std::vector<Issue> notes;
    for (const std::string& item : s.prior_items) {
        id::Priors scratch;
        std::vector<std::string> deprecated;
        id::parsePriorItem(item, scratch, &deprecated);
        for (std::string& note : deprecated) notes.push_back({"priors", std::move(note)});
    }
    return notes;
}

void noteDeprecatedParameterKeys(io::ObjectReader& r, IdentificationSettings& out,
                                 const char* priors_key) {
    // The old keys of the parameters (issue 26) are read as their new ones and noted.
    for (const Issue& note : deprecatedPriorItems(out))
        out.key_warnings.push_back({r.where(priors_key), note.message});
    for (std::string& item : out.prior_items) item = id::canonicalPriorItem(item);
    if (const nlohmann::json* fix = r.has("fix") ? r.value("fix") : nullptr;
        fix && fix->is_object()) {
        for (const id::DeprecatedParameterKey& old : id::deprecatedParameterKeys()) {
            if (fix->contains(old.old_key))
                out.key_warnings.push_back(
                    {r.where("fix." + std::string(old.old_key)), id::deprecationNote(old.old_key)});
        }
    }
}

void readIdentificationSettings(io::ObjectReader& r, const ReadContext& context,
                                IdentificationSettings& out) {
    io::readFields(r, out, context.base_dir);
    if (!out.csv.empty() && r.has("csv")) {
        // Read as the fit will use it: the full model reads a file without an entry angle.
        auto read = id::readDataSet(
            out.csv, out.skip_bad_rows ? id::BadRows::kSkip : id::BadRows::kStop, needsOf(out));
        if (!read) {
            for (const Issue& issue : read.issues())
                r.report("csv", issue.where + ": " + issue.message);
        } else if (read->data.samples.empty()) {
            r.report("csv", out.csv + ": no valid samples");
        } else {
            out.data = read->data;
            for (const Issue& issue : read->warnings)
                out.data_warnings.push_back(issue.where + ": " + issue.message);
        }
    }
    for (const Issue& issue : identificationRuleIssues(out)) r.report(issue.where, issue.message);
    for (std::string& item : out.prior_items) {
        id::Priors scratch;
        for (const Issue& issue : id::parsePriorItem(item, scratch))
            r.report("priors", issue.where + ": " + issue.message);
    }
    noteDeprecatedParameterKeys(r, out);
    if (!out.prior_soil_name.empty() && context.locations != nullptr) {
        Result<soil::SoilParameters> soil =
            io::resolveSoil(*context.locations, context.presetOrFile(out.prior_soil_name));
        if (soil) {
            out.prior_soil = soil.value();  // centred on the wheel when the analysis runs
        } else {
            r.report("prior_soil", soil.message());
        }
    }
}

std::optional<id::Loss> lossFromName(const std::string& name) {
    if (name == "l2" || name == "squared") return id::Loss::kSquared;
    if (name == "huber") return id::Loss::kHuber;
    if (name == "cauchy") return id::Loss::kCauchy;
    return std::nullopt;
}

const char* lossName(id::Loss loss) {
    switch (loss) {
        case id::Loss::kHuber:
            return "huber";
        case id::Loss::kCauchy:
            return "cauchy";
        case id::Loss::kSquared:
            break;
    }
    return "l2";
}

id::Priors priorsOf(const IdentificationSettings& s, const wheel::WheelParameters& wheel,
                    std::string* source) {
    id::Priors priors{};
    std::string text;
    if (s.prior_soil) {
        priors = id::priorsFromSoil(*s.prior_soil, wheel);
        text = (s.prior_soil_name.empty() ? s.prior_soil->name : s.prior_soil_name) + " preset";
    }
    std::vector<Issue> issues;
    for (const std::string& item : s.prior_items) {
        const std::vector<Issue> bad = id::parsePriorItem(item, priors);
        issues.insert(issues.end(), bad.begin(), bad.end());
        text += (text.empty() ? "" : " + ") + id::canonicalPriorItem(item);
    }
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    if (source != nullptr) *source = text;
    return priors;
}

id::IdentifyOptions identifyOptions(const IdentificationSettings& s,
                                    const wheel::WheelParameters& wheel, double jmax) {
    id::IdentifyOptions o;
    o.priors = priorsOf(s, wheel);
    o.load_n = s.load_n;
    o.max_shear_deformation_m = jmax;
    o.fit_max_shear_deformation = s.fit_max_shear_deformation;
    o.noise = {s.noise.fx_n, s.noise.fz_n, s.noise.my_nm, 0.0};
    o.loss = s.loss;
    o.starts = s.starts;
    o.design_points = s.design_points;
    o.holdout_fraction = s.holdout_fraction;
    o.folds = s.folds;
    for (const auto& [key, value] : s.fixed) {
        const IdentifiedField* field = id::lookupParameter(key).field;
        if (field == nullptr) continue;
        if (const auto k = fullParameterOf(*field))
            o.fixed[static_cast<std::size_t>(*k)] = field->toSi(value);
    }
    return o;
}

nlohmann::json toJson(const IdentificationSettings& s) { return io::fieldsToJson(s); }

namespace {

// Parameters in the output's keys and units (identified_parameters.h) from SI values.
nlohmann::json userJson(const id::ParameterVector& si) {
    nlohmann::json j = nlohmann::json::object();
    for (int k = 0; k < id::kFullParameterCount; ++k) {
        const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
        j[field.key] = si[static_cast<std::size_t>(k)] / field.to_si;
    }
    return j;
}

// Per-channel values of the channels in use, by column name.
nlohmann::json channelJson(const id::ChannelValues& values,
                           const std::array<bool, id::kChannelCount>& used) {
    nlohmann::json j = nlohmann::json::object();
    for (std::size_t c = 0; c < id::kChannelCount; ++c) {
        if (used[c]) j[id::channelNames()[c]] = values[c];
    }
    return j;
}

// The keys the global identification adds: prior, holdout, ambiguity, gradient_norm (and what
// the fit started from, its data source, χ², noise levels, the covariance).
void addGlobalJson(const IdentificationResult& result, nlohmann::json& j) {
    const id::IdentificationReport& r = *result.report;
    j["covariance"] = covarianceJson(r);
    nlohmann::json prior = nlohmann::json::object();
    for (int k = 0; k < id::kFullParameterCount; ++k) {
        const id::PriorComparison& c = r.prior[static_cast<std::size_t>(k)];
        if (!c.active) continue;
        const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
        prior[field.key] = {{"prior_mean", c.prior_mean / field.to_si},
                            {"prior_std", c.prior_std / field.to_si},
                            {"posterior_mean", c.posterior_mean / field.to_si},
                            {"posterior_std", c.posterior_std / field.to_si},
                            {"shift_in_prior_std", c.shift_in_prior_std},
                            {"std_ratio", c.std_ratio}};
    }
    j["prior"] = prior.empty() ? nlohmann::json() : prior;
    if (r.holdout.computed) {
        j["holdout"] = {
            {"folds", r.holdout.folds},
            {"samples", r.holdout.samples},
            {"failed", r.holdout.failed},
            {"rms", channelJson(r.holdout.rms, r.holdout.channels)},
            {"rms_in_fit", channelJson(r.holdout.rms_in_fit, r.holdout.channels)},
            {"rms_over_noise", channelJson(r.holdout.rms_over_noise, r.holdout.channels)}};
    } else {
        j["holdout"] = nullptr;
    }
    nlohmann::json ambiguity = nlohmann::json::array();
    for (const id::Minimum& m : r.ambiguity) {
        ambiguity.push_back({{"parameters", userJson(m.parameters)},
                             {"std", userJson(m.std)},
                             {"chi2", m.chi2},
                             {"delta_chi2", m.delta_chi2},
                             {"start", m.label}});
    }
    j["ambiguity"] = ambiguity;
    j["ambiguity_delta_chi2"] = r.ambiguity_delta_chi2;
    j["gradient_norm"] = r.gradient_norm;
    j["newton_decrement"] = r.newton_decrement;
    j["chi2"] = r.chi2;
    j["start"] = result.start_description;
    j["source"] = r.setup.description;
    j["noise"] = channelJson(r.noise, r.setup.channels);
    j["noise_estimated"] = r.noise_estimated;
    // adequacy: per channel the trend test of the residuals in slip (null where not tested),
    // the smallest p and whether it flags a systematic misfit.
    nlohmann::json channels = nlohmann::json::object();
    for (std::size_t c = 0; c < id::kChannelCount; ++c) {
        if (!r.setup.channels[c]) continue;
        const id::TrendTest& t = r.adequacy.trend[c];
        channels[id::channelNames()[c]] =
            t.tested() ? nlohmann::json{{"p", t.p},
                                        {"F", t.f},
                                        {"trend_share", t.trend_share},
                                        {"dof", {t.trend_dof, t.values - t.trend_dof}}}
                       : nlohmann::json();
    }
    j["adequacy"] = {{"p", r.adequacy.p}, {"flag", r.adequacy.flag}, {"channels", channels}};
    // profile_interval: per parameter profiled (profile), the interval in the output's units and
    // whether the profile reached a bound before Δχ²; null without it.
    nlohmann::json profile = nlohmann::json::object();
    for (int k = 0; k < id::kFullParameterCount; ++k) {
        const id::ProfileInterval& p = result.profile[static_cast<std::size_t>(k)];
        if (!p.computed) continue;
        const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
        profile[field.key] = {
            {"lower", p.lower / field.to_si},     {"upper", p.upper / field.to_si},
            {"lower_at_bound", p.lower_at_bound}, {"upper_at_bound", p.upper_at_bound},
            {"delta_chi2", p.delta_chi2},         {"fits", p.fits}};
    }
    j["profile_interval"] = profile.empty() ? nlohmann::json() : profile;
}

}  // namespace

nlohmann::json identifiedJson(const id::DecoupledParameters& p) {
    nlohmann::json j = nlohmann::json::object();
    for (const IdentifiedField& field : identifiedFields()) j[field.key] = field.userValue(p);
    return j;
}

nlohmann::json fullParametersJson(const id::ParameterVector& si) { return userJson(si); }

nlohmann::json covarianceJson(const id::IdentificationReport& r) {
    const id::Uncertainty& u = r.uncertainty;
    if (!u.computed) return nullptr;
    std::vector<std::size_t> free;
    for (std::size_t k = 0; k < id::kFullParameterCount; ++k) {
        if (u.std[k] > 0.0 && std::isfinite(u.std[k])) free.push_back(k);
    }
    if (free.empty()) return nullptr;
    nlohmann::json names = nlohmann::json::array(), mean = nlohmann::json::array(),
                   covariance = nlohmann::json::array();
    for (std::size_t a : free) {
        const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(a));
        names.push_back(field.key);
        mean.push_back(field.toUser(r.parameters[a]));
        nlohmann::json row = nlohmann::json::array();
        for (std::size_t b : free) {
            const IdentifiedField& other = fieldOf(static_cast<id::FullParameter>(b));
            // Σ_ab = σ_a σ_b ρ_ab in the display units (each std divided by its field's
            // to_si, as the "std" output); ρ made exactly symmetric, the diagonal exactly σ².
            const double rho = a == b ? 1.0 : 0.5 * (u.correlation[a][b] + u.correlation[b][a]);
            row.push_back((u.std[a] / field.to_si) * (u.std[b] / other.to_si) * rho);
        }
        covariance.push_back(std::move(row));
    }
    return {{"parameters", names}, {"mean", mean}, {"covariance", covariance}};
}

nlohmann::json toJson(const IdentificationResult& result) {
    nlohmann::json j = identifiedJson(result.identified);
    if (result.report) {
        const id::Uncertainty& u = result.report->uncertainty;
        nlohmann::json std_json = nlohmann::json::object();
        for (int k = 0; k < id::kFullParameterCount; ++k) {
            const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
            std_json[field.key] =
                u.computed ? nlohmann::json(u.std[static_cast<std::size_t>(k)] / field.to_si)
                           : nlohmann::json();
        }
        j["std"] = std_json;
        j["flags"] = id::worded(u.flags, id::ParameterNaming::kKey);
    }
    nlohmann::json steps = nlohmann::json::array();
    for (const id::StepReport& step : result.steps()) {
        steps.push_back({{"step", step.name.worded(id::ParameterNaming::kKey)},
                         {"usable", step.usable},
                         {"termination", step.termination},
                         {"iterations", step.iterations},
                         {"squared_residual_norm", step.squared_residual_norm},
                         {"time_ms", step.wall_time_ms}});
    }
    j["steps"] = steps;
    j["samples"] = result.data.samples.size();
    if (result.report) addGlobalJson(result, j);
    return j;
}

namespace {

// The global identification's rows: where it started, its data and χ², the priors against the
// posterior, the held-out errors, the profile intervals, the other minima.
void addGlobalRows(const IdentificationResult& result, Summary& out) {
    using Emphasis = SummaryRow::Emphasis;
    const id::IdentificationReport& r = *result.report;
    out.push_back({"started from", result.start_description, "", "", Emphasis::kNormal, "/start"});
    out.push_back({"data", r.setup.description, "", "", Emphasis::kNormal, "/source"});
    out.push_back({"chi2", formatNumber(roundSignificant(r.chi2, 5)), "", "", Emphasis::kNormal,
                   "/chi2", r.chi2});
    // (The gradient's norm stays in the JSON, "gradient_norm": a solver's diagnostic, which the
    // next row says in a user's words.)
    // The Newton decrement gᵀH⁻¹g in a user's words (issue 27): what one more step would still
    // gain in χ², against the change of 1 that is one std.
    const bool at_minimum = r.newton_decrement < 0.1;
    out.push_back({"one more step would lower chi2 by",
                   formatNumber(roundSignificant(r.newton_decrement, 3)), "",
                   at_minimum ? "at a minimum: less than 0.1, where a change of 1 is one std"
                              : "not clearly at a minimum, where a change of 1 is one std: fit "
                                "again, or fix or give priors to the parameters the data do not "
                                "determine",
                   at_minimum ? Emphasis::kNormal : Emphasis::kWarning, "/newton_decrement",
                   r.newton_decrement});
    bool header = false;
    for (int k = 0; k < id::kFullParameterCount; ++k) {
        const id::PriorComparison& c = r.prior[static_cast<std::size_t>(k)];
        if (!c.active) continue;
        const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
        if (!header) {
            out.push_back({"prior -> posterior", "", "", "shift in prior std, posterior/prior std",
                           Emphasis::kHeading, "/prior"});
        }
        header = true;
        out.push_back({field.symbol,
                       formatNumber(roundSignificant(c.prior_mean / field.to_si, 4)) + " ± " +
                           formatNumber(roundSignificant(c.prior_std / field.to_si, 3)) + " -> " +
                           formatNumber(roundSignificant(c.posterior_mean / field.to_si, 4)) +
                           " ± " + formatNumber(roundSignificant(c.posterior_std / field.to_si, 3)),
                       field.displayUnit(),
                       formatFixed(c.shift_in_prior_std, 2) + ", " + formatFixed(c.std_ratio, 2),
                       Emphasis::kNormal, "/prior/" + std::string(field.key) + "/prior_mean",
                       c.prior_mean / field.to_si});
    }
    if (r.holdout.computed) {
        out.push_back({"held-out RMS in noise std",
                       std::to_string(r.holdout.samples) + " samples, " +
                           std::to_string(r.holdout.folds) + " fold(s)",
                       "", "", Emphasis::kHeading, "/holdout"});
        for (std::size_t c = 0; c < id::kChannelCount; ++c) {
            if (!r.holdout.channels[c]) continue;
            const std::string name = id::channelNames()[c];
            out.push_back({name, formatFixed(r.holdout.rms_over_noise[c], 2), "",
                           "RMS " + formatNumber(roundSignificant(r.holdout.rms[c], 3)) +
                               ", in fit " + formatFixed(r.holdout.rms_in_fit[c] / r.noise[c], 2),
                           Emphasis::kNormal, "/holdout/rms_over_noise/" + name,
                           r.holdout.rms_over_noise[c]});
        }
    } else {
        out.push_back({"held-out error", "not computed", "", "give a holdout fraction or folds",
                       Emphasis::kNormal, ""});
    }
    // Whether the residuals are noise (the trend test in slip of each channel, adequacy.h).
    out.push_back({"adequacy, smallest p", formatNumber(roundSignificant(r.adequacy.p, 2)), "",
                   r.adequacy.flag ? "systematic misfit: the residuals follow slip, so the "
                                     "estimate is biased and its std too small (a note says "
                                     "where; a shear limit? identify j_max)"
                                   : "the residuals look like noise",
                   r.adequacy.flag ? Emphasis::kWarning : Emphasis::kNormal,
                   std::isfinite(r.adequacy.p) ? "/adequacy/p" : "", r.adequacy.p});
    bool profile_header = false;
    for (int k = 0; k < id::kFullParameterCount; ++k) {
        const id::ProfileInterval& p = result.profile[static_cast<std::size_t>(k)];
        if (!p.computed) continue;
        const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
        if (!profile_header) {
            out.push_back({"profile-likelihood intervals",
                           "delta chi2 = " + formatNumber(roundSignificant(p.delta_chi2, 3)), "",
                           "the 3-std level", Emphasis::kHeading, "/profile_interval"});
        }
        profile_header = true;
        out.push_back({field.symbol,
                       formatNumber(roundSignificant(p.lower / field.to_si, 4)) +
                           (p.lower_at_bound ? " (bound)" : "") + " .. " +
                           formatNumber(roundSignificant(p.upper / field.to_si, 4)) +
                           (p.upper_at_bound ? " (bound)" : ""),
                       field.displayUnit(), "", Emphasis::kNormal,
                       "/profile_interval/" + std::string(field.key) + "/lower",
                       p.lower / field.to_si});
    }
    if (r.ambiguity.empty()) {
        out.push_back({"ambiguity", "none", "",
                       "no other minimum within delta chi2 = " +
                           formatNumber(roundSignificant(r.ambiguity_delta_chi2, 3)),
                       Emphasis::kNormal, ""});
    }
    for (const id::Minimum& minimum : r.ambiguity) {
        std::string text = "another minimum with delta chi2 = " +
                           formatNumber(roundSignificant(minimum.delta_chi2, 3)) + " (threshold " +
                           formatNumber(roundSignificant(r.ambiguity_delta_chi2, 3)) + "):";
        for (int k = 0; k < id::kFullParameterCount; ++k) {
            const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
            text.append(" ").append(field.symbol).append(" = ");
            text += formatNumber(
                roundSignificant(minimum.parameters[static_cast<std::size_t>(k)] / field.to_si, 4));
        }
        out.push_back({"AMBIGUOUS", text, "", "", Emphasis::kWarning, ""});
    }
}

}  // namespace

int displayDecimals(const IdentifiedField& field) {
    const std::string key = field.key;
    return key == "Ks_kPa" ? 1 : key == "c_kPa" ? 3 : key == "phi_deg" ? 2 : 4;
}

Summary identificationSummary(const IdentificationResult& result) {
    using Emphasis = SummaryRow::Emphasis;
    Summary out;
    const bool refined = result.report.has_value();
    out.push_back(
        {refined ? "full-model identification (global search)" : "decoupled identification",
         result.wheel, "", "", Emphasis::kHeading, ""});
    if (result.status != Outcome::Status::kCompleted) {
        out.push_back({result.status == Outcome::Status::kCancelled ? "cancelled" : "invalid input",
                       result.message, "", "", Emphasis::kWarning, ""});
        return out;
    }
    out.push_back({"samples", std::to_string(result.data.samples.size()), "", "", Emphasis::kNormal,
                   "/samples", static_cast<double>(result.data.samples.size())});
    const id::DecoupledParameters& p = result.identified;
    const std::optional<id::Uncertainty> uncertainty =
        refined ? std::optional(result.report->uncertainty) : std::nullopt;
    for (const IdentifiedField& field : identifiedFields()) {
        const auto full = fullParameterOf(field);
        if (refined && !full) continue;  // n1 = 0 after the refinement
        const bool limit = full == id::kJmax;
        if (limit && !refined) continue;  // the decoupled model has no j_max
        const double value = field.toUser(p.*field.member);
        SummaryRow row{field.symbol,
                       formatFixed(value, displayDecimals(field)),
                       field.displayUnit(),
                       "",
                       Emphasis::kNormal,
                       "/" + std::string(field.key),
                       value};
        if (uncertainty && uncertainty->computed && full) {
            // With a std: the value to the decimal place the std supports (formatAtStd).
            const double sd = uncertainty->std[static_cast<std::size_t>(*full)] / field.to_si;
            if (sd > 0) row.value = formatAtStd(value, sd) + " ± " + formatStd(sd);
        }
        if (limit && !std::isfinite(p.*field.member)) {
            row.value = "none";
            row.unit.clear();
            row.json.clear();
            row.number = std::numeric_limits<double>::quiet_NaN();
        }
        if (limit && !result.report->setup.max_shear_deformation_free) row.detail = "held";
        out.push_back(std::move(row));
    }
    const std::vector<id::StepReport> steps = result.steps();
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const id::StepReport& step = steps[i];
        std::string detail = formatFixed(step.wall_time_ms, 2) + " ms";
        if (!step.termination.empty()) detail += ", " + id::solverOutcome(step.termination);
        out.push_back({"step " + step.name.worded(id::ParameterNaming::kSymbol) + ", |r|^2",
                       formatNumber(roundSignificant(step.squared_residual_norm, 6)), "", detail,
                       Emphasis::kNormal, "/steps/" + std::to_string(i) + "/squared_residual_norm",
                       step.squared_residual_norm});
    }
    if (refined) {
        addGlobalRows(result, out);
        // The advice names the parameters by symbol here, by key in the JSON (/flags).
        const std::vector<std::string> flags =
            id::worded(result.report->uncertainty.flags, id::ParameterNaming::kSymbol);
        for (std::size_t f = 0; f < flags.size(); ++f) {
            out.push_back(
                {"note", flags[f], "", "", Emphasis::kWarning, "/flags/" + std::to_string(f)});
        }
    }
    return out;
}

Result<soil::SoilParameters> identifiedSoilFile(const IdentificationResult& result,
                                                const soil::SoilParameters& base,
                                                const wheel::WheelParameters& wheel, double jmax) {
    soil::SoilParameters flat = base;
    flat.cohesive_modulus = 0.0;  // K_s wholly in k_φ: the soil is the identified one on any b
    flat.profile.reset();
    soil::SoilParameters soil = identification::soilOf(flat, wheel, result.identified);
    // The global identification's j_max is the model's (identified, or held at `jmax`).
    soil.max_shear_deformation_m = result.report ? result.identified.max_shear_deformation_m : jmax;
    // A parameter that ended on a bound of the fit which is also its field's (c = 0) may lie a
    // rounding outside it (−2e−17 kPa from the solver's coordinates): put it on the bound.
    for (const soil::SoilField& field : soil::soilFields()) {
        double& value = soil.*field.member;
        const double width = field.range.high - field.range.low;
        const double low = field.range.low * field.to_si, high = field.range.high * field.to_si;
        const double tolerance = 1e-12 * width * field.to_si;
        if (value < low && value >= low - tolerance) value = low;
        if (value > high && value <= high + tolerance) value = high;
    }
    std::vector<Issue> issues = soil::validate(soil);
    if (!issues.empty()) {
        for (Issue& issue : issues)
            issue.message = "the identified soil is not a valid soil: " + issue.message;
        return issues;
    }
    return soil;
}

nlohmann::json soilPosteriorJson(const IdentificationResult& result,
                                 const soil::SoilParameters& soil,
                                 const wheel::WheelParameters& wheel) {
    if (!result.report || !result.report->uncertainty.computed) return nullptr;
    const id::IdentificationReport& r = *result.report;
    // `soil` has k_c = 0: correlatedFromIdentification's k_φ is then K_s itself.
    const CorrelatedParameters c =
        correlatedFromIdentification(result.identified, r.uncertainty, soil, wheel);
    // Its keys are the parameters with a std, in FullParameter order; a parameter that ended at
    // a bound of the fit (c = 0) is held there: the posterior is the others' given it, the
    // Schur complement Σ_ff − Σ_fb Σ_bb⁻¹ Σ_bf (the covariance with it fixed), since draws on
    // both sides of the bound would be half of them no soil.
    std::vector<Eigen::Index> kept, held;
    Eigen::Index index = 0;
    for (std::size_t k = 0; k < id::kFullParameterCount; ++k) {
        if (!(r.uncertainty.std[k] > 0.0) || !std::isfinite(r.uncertainty.std[k])) continue;
        (r.at_bound[k] ? held : kept).push_back(index++);
    }
    if (kept.empty()) return nullptr;
    const auto n = static_cast<Eigen::Index>(c.keys.size());
    Eigen::MatrixXd sigma(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < n; ++j)
            sigma(i, j) = c.covariance[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    }
    Eigen::MatrixXd conditional = sigma(kept, kept);
    if (!held.empty()) {
        conditional -= sigma(kept, held) * sigma(held, held).ldlt().solve(sigma(held, kept));
        conditional = 0.5 * (conditional + conditional.transpose()).eval();
    }
    nlohmann::json keys = nlohmann::json::array(), mean = nlohmann::json::array(),
                   covariance = nlohmann::json::array();
    // In the identification's names and units (the interface of issue 25: "Ks_kPa", "n0", …;
    // the readers translate them back, soil_posterior.h).
    auto identificationName = [](const std::string& key) -> std::string {
        const id::ParameterField* field = id::parameterOfSoilKey(key);
        return field ? field->key : key;
    };
    for (std::size_t a = 0; a < kept.size(); ++a) {
        keys.push_back(identificationName(c.keys[static_cast<std::size_t>(kept[a])]));
        mean.push_back(c.mean[static_cast<std::size_t>(kept[a])]);
        std::vector<double> row;
        for (std::size_t b = 0; b < kept.size(); ++b)
            row.push_back(conditional(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
        covariance.push_back(row);
    }
    return {{"parameters", keys}, {"mean", mean}, {"covariance", covariance}};
}

std::vector<id::StepReport> IdentificationResult::steps() const {
    if (!report) {
        return fit.steps;
    }
    const id::IdentificationReport& r = *report;
    double best_screening = std::numeric_limits<double>::infinity();
    int descended = 0;
    for (const id::StartReport& start : r.starts) {
        best_screening = std::min(best_screening, start.screening_cost);
        descended += start.descended ? 1 : 0;
    }
    std::vector<id::StepReport> out;
    out.push_back({"screening: " + std::to_string(r.starts.size()) + " starts", !r.starts.empty(),
                   "best chi2 on the subset after the linear projection",
                   static_cast<int>(r.starts.size()),
                   std::isfinite(best_screening) ? best_screening : 0.0, r.timing.screening_ms});
    out.push_back({"descent: " + std::to_string(descended) + " best starts on the subset",
                   descended > 0, "", descended, 0.0, r.timing.descent_ms});
    out.push_back({"refinement: " + std::to_string(r.minima.size()) + " minima on all samples",
                   r.usable(), r.termination, r.iterations, r.chi2,
                   r.timing.refinement_ms + r.timing.covariance_ms});
    if (r.holdout.computed) {
        std::string text = std::to_string(r.holdout.samples) + " samples predicted";
        if (r.holdout.failed > 0) text += ", " + std::to_string(r.holdout.failed) + " failed";
        text += "; RMS / noise std";
        for (std::size_t c = 0; c < id::kChannelCount; ++c) {
            if (r.holdout.channels[c]) {
                text += " " + std::string(id::channelNames()[c]) + " " +
                        formatNumber(roundSignificant(r.holdout.rms_over_noise[c], 3));
            }
        }
        out.push_back({"held-out: " + std::to_string(r.holdout.folds) + " fold(s)",
                       r.holdout.samples > r.holdout.failed, text, r.holdout.folds, 0.0,
                       r.timing.holdout_ms});
    }
    return out;
}

bool IdentificationResult::usable() const {
    if (!message.empty()) return false;
    if (report) return report->usable();
    return fit.usable();
}

IdentificationResult computeIdentification(const Inputs& in, const IdentificationSettings& s,
                                           const Control& control) {
    // The reader's checks, in its words, for settings built in code (a panel's, Python's).
    std::vector<Issue> issues = io::fieldIssues(s);
    for (Issue& issue : identificationRuleIssues(s)) issues.push_back(std::move(issue));
    if (!s.prior_soil_name.empty() && !s.prior_soil)
        issues.push_back({"prior_soil", quoteText(s.prior_soil_name) + " is not resolved"});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    IdentificationResult out;
    out.wheel = in.wheel.name;
    loadData(in, s, out);
    for (const Issue& note : s.key_warnings)
        out.warnings.push_back(note.where + ": " + note.message);
    // Settings built in code (a panel's typed prior items) may name a parameter by an old key
    // too: read as its new one, noted as the reader notes it.
    for (const Issue& note : deprecatedPriorItems(s))
        out.warnings.push_back(note.where + ": " + note.message);
    for (const auto& [key, value] : s.fixed) {
        if (id::lookupParameter(key).deprecated)
            out.warnings.push_back("fix." + key + ": " + id::deprecationNote(key));
    }
    if (!out.message.empty()) return out;
    if (out.data.samples.empty()) {
        out.status = Outcome::Status::kInvalidInput;
        out.message = "the data set has no samples";
        return out;
    }
    // A CSV's fit never depends on the inputs' soil: its j_max is the settings' (none by
    // default); synthetic data were made from the inputs' soil, whose j_max is their model's.
    const bool synthetic = !s.data && s.csv.empty();
    const double jmax = s.max_shear_deformation_m.value_or(
        synthetic ? in.soil.max_shear_deformation_m : std::numeric_limits<double>::infinity());
    const auto start = std::chrono::steady_clock::now();
    id::DecoupledParameters p;
    std::vector<id::Prediction> predictions;
    if (s.refine) {
        std::string prior_source;
        priorsOf(s, in.wheel, &prior_source);
        id::IdentifyOptions options = identifyOptions(s, in.wheel, jmax);
        options.threads = control.threads;
        options.progress = [&control](double fraction) {
            control.report(fraction);
            return !control.cancelled();
        };
        out.report = id::identify(out.data, in.wheel, options);
        const id::IdentificationReport& r = *out.report;
        out.start_description =
            "global search: " + std::to_string(s.design_points) + " design points, no start needed";
        for (const id::Start& extra : s.starts) out.start_description += " + " + extra.label;
        if (!prior_source.empty()) out.start_description += "; prior: " + prior_source;
        if (r.status == id::IdentifyStatus::kInvalidInput) {
            out.status = Outcome::Status::kInvalidInput;
            out.message = formatIssues(r.issues);
            return out;
        }
        if (r.status == id::IdentifyStatus::kCancelled) {
            out.status = Outcome::Status::kCancelled;
            out.message = "cancelled";
            out.cancelled = true;
            return out;
        }
        p = id::decoupledOf(r.parameters);
        predictions = id::predictAll(out.data, in.wheel, r.parameters, options);
        if (s.profile && r.usable()) {
            const auto profile_start = std::chrono::steady_clock::now();
            out.profile = id::profileIntervals(out.data, in.wheel, options, r,
                                               id::tradeOffParameters(r, options.correlation_flag));
            out.profile_time_ms = std::chrono::duration<double, std::milli>(
                                      std::chrono::steady_clock::now() - profile_start)
                                      .count();
        }
    } else {
        if (!out.data.columns.entry_angle || !out.data.columns.fx || !out.data.columns.fz ||
            !out.data.columns.my) {
            out.status = Outcome::Status::kInvalidInput;
            out.message = "the decoupled fit needs entry_angle_deg, Fx_N, Fz_N and My_Nm";
            return out;
        }
        out.fit = id::fitDecoupled(out.data, in.wheel, s.guess);
        p = out.fit.parameters;
        if (in.wheel.lugShearOffset() > 0.0) {
            // The decoupled model (Eqs. 4.1–4.17) is the thesis's linearisation on the rim
            // radius; it has no shearing radius (docs/model.md, "Lugs").
            out.warnings.push_back(
                "the decoupled fit treats the lugged wheel as smooth (the lug model is only in "
                "the full model: refine)");
        }
        out.start_description =
            "decoupled three-step fit from fixed guesses (a0 = " + formatNumber(s.guess.a0) +
            ", phi = " + formatNumber(units::radToDeg(s.guess.friction_angle_rad)) + " deg, …)";
    }
    out.identified = p;
    out.fit_time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count() -
        out.profile_time_ms;

    out.curves.columns = {
        "slip",      "entry_angle_deg", "Fx_N",      "Fz_N", "My_Nm",
        "Fx_fit_N",  "Fz_fit_N",        "My_fit_Nm", "W_N",  "entry_angle_fit_deg",
        "sinkage_m", "sinkage_fit_m"};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const id::DataColumns& columns = out.data.columns;
    for (std::size_t i = 0; i < out.data.samples.size(); ++i) {
        const id::Sample& sample = out.data.samples[i];
        double fx = nan, fz = nan, my = nan, theta = nan, sinkage = nan;
        if (!predictions.empty()) {
            const id::Prediction& f = predictions[i];
            if (f.ok) {
                fx = f.values[id::kFxChannel];
                fz = f.values[id::kFzChannel];
                my = f.values[id::kMyChannel];
                sinkage = f.values[id::kSinkageChannel];
                theta = units::radToDeg(f.entry_angle_rad);
            }
        } else {
            // γ only enters bulldozing, left out here (the decoupled model's own forces).
            const auto f = id::decoupledForward(p, in.wheel, sample.slip, sample.entry_angle_rad);
            fx = f.fx_n;
            fz = f.fz_n;
            my = f.my_nm;
            theta = units::radToDeg(sample.entry_angle_rad);
            sinkage = in.wheel.radius_m * (1.0 - std::cos(sample.entry_angle_rad));
        }
        out.curves.rows.push_back(
            {sample.slip, measuredOr(columns.entry_angle, units::radToDeg(sample.entry_angle_rad)),
             measuredOr(columns.fx, sample.fx_n), measuredOr(columns.fz, sample.fz_n),
             measuredOr(columns.my, sample.my_nm), fx, fz, my,
             sample.load_n.value_or(s.load_n.value_or(nan)), theta, sample.sinkage_m.value_or(nan),
             sinkage});
    }
    std::vector<double> row;
    for (const IdentifiedField& field : identifiedFields()) {
        out.parameters.columns.emplace_back(field.key);
        row.push_back(field.toUser(p.*field.member));
    }
    if (out.report && out.report->uncertainty.computed) {
        const auto& sd = out.report->uncertainty.std;
        for (int k = 0; k < id::kFullParameterCount; ++k) {
            const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
            out.parameters.columns.push_back(std::string(field.key) + "_std");
            row.push_back(sd[static_cast<std::size_t>(k)] / field.to_si);
        }
    }
    out.parameters.rows.push_back(std::move(row));
    return out;
}

Outcome identificationOutcome(IdentificationResult result) {
    Outcome out;
    if (!result.message.empty()) {
        out.status = result.status;
        out.message = result.message;
    }
    out.tables.push_back({"parameters", "-parameters", result.parameters});
    out.tables.push_back({"curves", "", result.curves});
    out.notes = result.warnings;
    if (!result.start_description.empty()) out.notes.push_back(result.start_description);
    if (result.report && !result.report->ambiguity.empty()) {
        out.notes.push_back("ambiguous: " + std::to_string(result.report->ambiguity.size()) +
                            " other minimum(s) within delta chi2 " +
                            formatNumber(result.report->ambiguity_delta_chi2));
    }
    for (const Issue& skipped : result.skipped)
        out.notes.push_back("skipped " + skipped.where + ": " + skipped.message);
    for (const id::StepReport& step : result.steps()) {
        // A step without a termination or a residual (the descent, the held-out prediction)
        // says only what it did.
        std::string note = step.name.worded(id::ParameterNaming::kKey);
        if (!step.termination.empty()) note += ": " + id::solverOutcome(step.termination);
        if (step.squared_residual_norm > 0.0)
            note += ", Σr² = " + formatNumber(step.squared_residual_norm);
        out.notes.push_back(std::move(note));
    }
    // The whole result as `identify --json` prints it (Python's ts.identify returns it).
    if (result.message.empty()) out.documents.emplace_back("-identification.json", toJson(result));
    out.result = std::move(result);
    return out;
}

AnalysisType identificationType() {
    return makeAnalysisType<IdentificationSettings>(
        "identification",
        "soil parameters from wheel data (CSV or synthetic): global identification on the full "
        "model, or the decoupled fit alone (chapter 5, Figs. 5.1-5.6)",
        {"parameters", "curves"}, {{"Fx", "-Fx"}, {"Fz", "-Fz"}, {"My", "-My"}},
        readIdentificationSettings,
        [](const Inputs& in, const IdentificationSettings& s, const Control& c) {
            return computeIdentification(in, s, c);
        },
        identificationOutcome);
}

}  // namespace terra::analysis
