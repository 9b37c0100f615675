#include "core/analysis/global_sensitivity.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/analysis/sweep.h"
#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"
#include "core/io/parameters_json.h"
#include "core/soil/soil_parameters.h"

namespace terra::analysis {
namespace {

std::vector<std::string> soilKeys() {
    std::vector<std::string> keys;
    for (const soil::SoilField& f : soil::soilFields()) keys.emplace_back(f.key);
    return keys;
}

// "phi_deg" is not a soil field (did you mean …?), or the field.
const soil::SoilField* soilField(const std::string& key, std::vector<Issue>& issues,
                                 const std::string& where) {
    const soil::SoilField* field = soil::findSoilField(key);
    if (!field) {
        const std::vector<std::string> keys = soilKeys();
        const std::string near = nearestName(key, keys);
        std::string all;
        for (const std::string& k : keys) all += (all.empty() ? "" : ", ") + k;
        issues.push_back({where, quoteText(key, '"') + " is not a soil field" +
                                     (near.empty() ? "" : " (did you mean \"" + near + "\"?)") +
                                     "; fields: " + all});
    }
    return field;
}

// A value of a parameter's distribution inside its soil field's range.
void checkInField(std::vector<Issue>& issues, const std::string& where,
                  const soil::SoilField& field, double value) {
    checkRange(issues, where, value, field.range, field.displayUnit());
}

// Every problem of the parameters: unknown or repeated keys, ranges and bounds outside their
// field's, empty ranges, sd ≤ 0, a correlated group of the wrong shape.
std::vector<Issue> parameterIssues(const StudyDefinition& d) {
    std::vector<Issue> issues;
    std::vector<std::string> seen;
    auto repeated = [&](const std::string& key, const std::string& where) {
        for (const std::string& s : seen) {
            if (s == key) issues.push_back({where, quoteText(key, '"') + " is varied twice"});
        }
        seen.push_back(key);
    };
    for (std::size_t i = 0; i < d.parameters.size(); ++i) {
        const UncertainParameter& p = d.parameters[i];
        const std::string where = "parameters[" + std::to_string(i) + "]";
        repeated(p.key, where + ".key");
        const soil::SoilField* field = soilField(p.key, issues, where + ".key");
        if (const auto* u = std::get_if<gsa::Uniform>(&p.distribution)) {
            if (field) {
                checkInField(issues, where + ".range[0]", *field, u->low);
                checkInField(issues, where + ".range[1]", *field, u->high);
            }
            if (!(u->low < u->high)) {
                issues.push_back({where + ".range", "low " + formatNumber(u->low) +
                                                        " must be below high " +
                                                        formatNumber(u->high)});
            }
        } else {
            const auto& n = std::get<gsa::Normal>(p.distribution);
            if (!(n.sd > 0.0) || !std::isfinite(n.sd)) {
                issues.push_back(
                    {where + ".normal[1]", "sd " + formatNumber(n.sd) + " must be above 0"});
            }
            if (!std::isfinite(n.mean)) {
                issues.push_back({where + ".normal[0]", "mean must be finite"});
            }
            if (field && std::isfinite(n.low))
                checkInField(issues, where + ".bounds[0]", *field, n.low);
            if (field && std::isfinite(n.high))
                checkInField(issues, where + ".bounds[1]", *field, n.high);
            if (!(n.low < n.high)) {
                issues.push_back(
                    {where + ".bounds",
                     "low " + formatNumber(n.low) + " must be below high " + formatNumber(n.high)});
            }
        }
    }
    if (d.correlated) {
        const CorrelatedParameters& c = *d.correlated;
        const std::size_t k = c.keys.size();
        if (k == 0) issues.push_back({"correlated.keys", "no parameters"});
        for (std::size_t i = 0; i < k; ++i) {
            const std::string where = "correlated.keys[" + std::to_string(i) + "]";
            repeated(c.keys[i], where);
            soilField(c.keys[i], issues, where);
        }
        if (c.mean.size() != k) {
            issues.push_back({"correlated.mean", std::to_string(c.mean.size()) + " values for " +
                                                     std::to_string(k) + " keys"});
        }
        bool square = c.covariance.size() == k;
        for (const auto& row : c.covariance) square = square && row.size() == k;
        if (!square) {
            issues.push_back(
                {"correlated.covariance",
                 "must be " + std::to_string(k) + "×" + std::to_string(k) + " (one row per key)"});
        }
    }
    if (d.parameters.empty() && !d.correlated) {
        issues.push_back({"parameters", "no uncertain parameters: give at least one"});
    }
    return issues;
}

std::vector<Issue> definitionIssues(const StudyDefinition& d) {
    std::vector<Issue> issues = parameterIssues(d);
    if (d.outputs.empty()) issues.push_back({"outputs", "no outputs"});
    for (std::size_t i = 0; i < d.outputs.size(); ++i) {
        if (gsa::findOutput(d.outputs[i])) continue;
        const std::string near = nearestName(d.outputs[i], gsa::outputNames());
        std::string all;
        for (const std::string& n : gsa::outputNames()) all += (all.empty() ? "" : ", ") + n;
        issues.push_back({"outputs[" + std::to_string(i) + "]",
                          quoteText(d.outputs[i], '"') + " is not an output" +
                              (near.empty() ? "" : " (did you mean \"" + near + "\"?)") +
                              "; outputs: " + all});
    }
    if (d.slips.empty()) issues.push_back({"slips", "no slips"});
    if (d.slip_angles_deg.empty()) issues.push_back({"slip_angles_deg", "no slip angles"});
    if (d.load_n && d.entry_angle_deg) {
        issues.push_back({"entry_angle_deg", "give load_N or entry_angle_deg, not both"});
    }
    return issues;
}

gsa::ParameterSpace spaceOf(const StudyDefinition& d) {
    gsa::ParameterSpace space;
    for (const UncertainParameter& p : d.parameters) space.add(p.key, p.distribution);
    if (d.correlated) {
        const CorrelatedParameters& c = *d.correlated;
        const auto k = static_cast<Eigen::Index>(c.keys.size());
        Eigen::VectorXd mean(k);
        Eigen::MatrixXd cov(k, k);
        for (Eigen::Index i = 0; i < k; ++i) {
            mean(i) = c.mean[static_cast<std::size_t>(i)];
            for (Eigen::Index j = 0; j < k; ++j)
                cov(i, j) = c.covariance[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        }
        space.addMultivariateNormal(c.keys, mean, cov);
    }
    return space;
}

// Two numbers [a, b] of an array key.
bool readPair(io::ObjectReader& r, std::string_view key, double& a, double& b) {
    std::vector<double> values;
    if (!r.numbers(key, values, {-1e300, 1e300}, {}, 2, 2)) return false;
    a = values[0];
    b = values[1];
    return true;
}

gsa::RunControl runControl(const Control& control, int threads) {
    gsa::RunControl run;
    run.threads = threads;
    run.progress = control.progress;
    run.cancel = control.cancel;
    return run;
}

Outcome::Status statusOf(gsa::StudyStatus status) {
    switch (status) {
        case gsa::StudyStatus::kCompleted:
            return Outcome::Status::kCompleted;
        case gsa::StudyStatus::kCancelled:
            return Outcome::Status::kCancelled;
        case gsa::StudyStatus::kTooManyFailures:
            return Outcome::Status::kFailed;
    }
    return Outcome::Status::kFailed;
}

nlohmann::json matrixJson(const Eigen::MatrixXd& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        nlohmann::json row = nlohmann::json::array();
        for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j) == 0.0 ? 0.0 : m(i, j));
        rows.push_back(std::move(row));
    }
    return rows;
}

Eigen::MatrixXd outputBlock(const Eigen::MatrixXd& m, std::size_t output, std::size_t points) {
    if (m.size() == 0) return {};
    return m.middleCols(static_cast<Eigen::Index>(output * points),
                        static_cast<Eigen::Index>(points));
}

}  // namespace

void readUncertainParameters(io::ObjectReader& r, const char* key,
                             std::vector<UncertainParameter>& out) {
    const nlohmann::json* array = r.array(key);
    if (!array) return;
    out.clear();
    for (std::size_t i = 0; i < array->size(); ++i) {
        io::ObjectReader e = r.element(key, *array, i);
        UncertainParameter p;
        // Checked against the soil fields with the other problems (studyRuleIssues).
        e.text("key", p.key, io::Presence::kRequired);
        const bool uniform = e.has("range"), normal = e.has("normal");
        if (uniform == normal) {
            e.report({}, "give \"range\": [low, high] or \"normal\": [mean, sd], one of them");
        }
        if (uniform) {
            gsa::Uniform u;
            readPair(e, "range", u.low, u.high);
            p.distribution = u;
        } else {
            gsa::Normal n;
            readPair(e, "normal", n.mean, n.sd);
            if (e.has("bounds")) readPair(e, "bounds", n.low, n.high);
            p.distribution = n;
        }
        if (uniform && e.has("bounds")) e.report("bounds", "bounds are for a normal distribution");
        e.allow("bounds");
        e.finish();
        out.push_back(std::move(p));
    }
}

nlohmann::json writeUncertainParameters(const std::vector<UncertainParameter>& parameters) {
    nlohmann::json out = nlohmann::json::array();
    for (const UncertainParameter& p : parameters) {
        nlohmann::json item{{"key", p.key}};
        if (const auto* u = std::get_if<gsa::Uniform>(&p.distribution)) {
            item["range"] = {u->low, u->high};
        } else {
            const auto& n = std::get<gsa::Normal>(p.distribution);
            item["normal"] = {n.mean, n.sd};
            if (std::isfinite(n.low) && std::isfinite(n.high)) item["bounds"] = {n.low, n.high};
        }
        out.push_back(std::move(item));
    }
    return out;
}

void readCorrelatedParameters(io::ObjectReader& r, const char* key,
                              std::optional<CorrelatedParameters>& out) {
    if (!r.has(key)) {
        r.allow(key);
        return;
    }
    io::ObjectReader c = r.object(key);
    CorrelatedParameters group;
    c.texts("keys", group.keys, io::Presence::kRequired);
    c.numbers("mean", group.mean, {-1e300, 1e300}, {}, 1, 100, io::Presence::kRequired);
    if (const nlohmann::json* rows = c.array("covariance", io::Presence::kRequired)) {
        for (std::size_t i = 0; i < rows->size(); ++i) {
            const nlohmann::json& row = (*rows)[i];
            std::vector<double> values;
            bool ok = row.is_array();
            for (std::size_t j = 0; ok && j < row.size(); ++j) {
                ok = row[j].is_number() && std::isfinite(row[j].get<double>());
                if (ok) values.push_back(row[j].get<double>());
            }
            if (!ok) {
                c.report("covariance", "row " + std::to_string(i) +
                                           " must be an array of finite numbers, got " +
                                           io::describeJson(row));
            }
            group.covariance.push_back(std::move(values));
        }
    }
    c.finish();
    out = std::move(group);
}

nlohmann::json writeCorrelatedParameters(const std::optional<CorrelatedParameters>& group) {
    if (!group) return nullptr;
    return {{"keys", group->keys}, {"mean", group->mean}, {"covariance", group->covariance}};
}

void readSampleCount(io::ObjectReader& r, const char* key, std::size_t& out) {
    int samples = static_cast<int>(out);
    if (r.integer(key, samples, 2, 1 << 24)) out = static_cast<std::size_t>(samples);
}

nlohmann::json writeSampleCount(const std::size_t& samples) { return samples; }

void readCompactionStudyKey(io::ObjectReader& r, const char* key, gsa::CompactionStudy& out) {
    if (!r.has(key)) {
        r.allow(key);
        return;
    }
    io::ObjectReader c = r.object(key);
    readCompactionStudy(c, out);
    c.finish();
}

nlohmann::json writeCompactionStudy(const gsa::CompactionStudy& study) {
    nlohmann::json out{
        {"depth_m", study.depth_m},
        {"passes", study.passes},
        {"risk_stress", study.measure == compaction::RiskMeasure::kMajor ? "sigma_1" : "sigma_z"}};
    if (study.concentration) out["concentration"] = *study.concentration;
    if (study.profile) out["profile"] = io::toJson(*study.profile);
    return out;
}

std::vector<Issue> studyRuleIssues(const StudyDefinition& d, bool slips_needed) {
    std::vector<Issue> issues;
    for (Issue& issue : definitionIssues(d)) {
        if (!slips_needed && issue.where == "slips") continue;
        issues.push_back(std::move(issue));
    }
    // The variance decomposition needs a valid space: the covariance's definiteness is checked
    // by building it.
    if (parameterIssues(d).empty()) {
        try {
            spaceOf(d);
        } catch (const std::invalid_argument& e) {
            issues.push_back({d.correlated ? "correlated" : "parameters", e.what()});
        }
    }
    return issues;
}

void readCompactionStudy(io::ObjectReader& c, gsa::CompactionStudy& study) {
    c.number("depth_m", study.depth_m, Range{0.0, 10.0, true}, "m");
    c.integer("passes", study.passes, 1, 100);
    double nu = 0.0;
    if (c.number("concentration", nu, Range{2.5, 12.0})) study.concentration = nu;
    c.choice("risk_stress", study.measure,
             {{"sigma_z", compaction::RiskMeasure::kVertical},
              {"sigma_1", compaction::RiskMeasure::kMajor}});
    if (c.has("profile")) {
        io::ObjectReader p = c.object("profile");
        study.profile = io::readProfile(p);
        p.finish();
    }
}

gsa::WheelStudy wheelStudyOf(const Inputs& in, const StudyDefinition& d) {
    std::vector<Issue> issues = definitionIssues(d);
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    gsa::WheelStudy study;
    study.soil = in.soil;
    study.wheel = in.wheel;
    study.model.exit = d.model.exit;
    study.model.max_stress_angle_rad = d.model.max_stress_angle_rad;
    study.model.bulldozing = d.model.bulldozing;
    study.model.model = in.conditions.model();
    study.grid.slips = d.slips;
    study.grid.slip_angles_rad.clear();
    for (double beta : d.slip_angles_deg)
        study.grid.slip_angles_rad.push_back(units::degToRad(beta));
    if (d.entry_angle_deg) {
        study.grid.load_n.reset();
        study.grid.entry_angle_rad = units::degToRad(*d.entry_angle_deg);
    } else {
        study.grid.load_n = d.load_n.value_or(in.conditions.load_n);
    }
    study.outputs.clear();
    for (const std::string& name : d.outputs) study.outputs.push_back(*gsa::findOutput(name));
    study.parameters = spaceOf(d);
    study.compaction = d.compaction;
    gsa::requireValid(study);
    return study;
}

void readStudyDefinition(io::ObjectReader& r, StudyDefinition& out) {
    io::readFields(r, out);
    for (Issue& issue : studyRuleIssues(out)) r.report(issue.where, std::move(issue.message));
}

std::vector<Issue> globalSensitivityRuleIssues(const GlobalSensitivitySettings& s) {
    std::vector<Issue> issues = studyRuleIssues(s.study);
    if (s.levels % 2 != 0) issues.push_back({"levels", std::to_string(s.levels) + " must be even"});
    if (s.method == GsaMethod::kMorris) {
        for (std::size_t i = 0; i < s.study.parameters.size(); ++i) {
            if (!std::holds_alternative<gsa::Uniform>(s.study.parameters[i].distribution)) {
                issues.push_back({"parameters[" + std::to_string(i) + "]",
                                  "Morris screening needs ranges, not distributions"});
            }
        }
        if (s.study.correlated) issues.push_back({"correlated", "Morris screening needs ranges"});
    }
    return issues;
}

void readGlobalSensitivitySettings(io::ObjectReader& r, GlobalSensitivitySettings& out) {
    io::readFields(r, out);
    for (Issue& issue : globalSensitivityRuleIssues(out))
        r.report(issue.where, std::move(issue.message));
}

nlohmann::json toJson(const GlobalSensitivitySettings& s) { return io::fieldsToJson(s); }

gsa::StudyStatus GlobalSensitivityResult::status() const {
    return sobol ? sobol->status : morris->status;
}
const std::string& GlobalSensitivityResult::message() const {
    return sobol ? sobol->message : morris->message;
}
const std::vector<std::string>& GlobalSensitivityResult::parameters() const {
    return sobol ? sobol->parameters : morris->parameters;
}
const std::vector<gsa::Output>& GlobalSensitivityResult::outputs() const {
    return sobol ? sobol->outputs : morris->outputs;
}
const gsa::OperatingGrid& GlobalSensitivityResult::grid() const {
    return sobol ? sobol->grid : morris->grid;
}

Table GlobalSensitivityResult::table() const {
    Table t;
    t.columns = {"slip_angle_deg", "slip"};
    const auto& params = parameters();
    const gsa::OperatingGrid& g = grid();
    for (gsa::Output o : outputs()) {
        const std::string name = gsa::outputName(o);
        for (const std::string& p : params) {
            if (sobol) {
                for (const char* index : {"_S1_", "_ST_"}) {
                    t.columns.push_back(name + index + p);
                    t.columns.push_back(name + index + p + "_conf");
                }
            } else {
                t.columns.push_back(name + "_mu_star_" + p);
                t.columns.push_back(name + "_mu_star_" + p + "_conf");
                t.columns.push_back(name + "_mu_" + p);
                t.columns.push_back(name + "_sigma_" + p);
            }
        }
        t.columns.push_back(name + (sobol ? "_samples" : "_trajectories"));
    }
    if (status() == gsa::StudyStatus::kTooManyFailures) return t;
    const std::size_t points = g.size();
    for (std::size_t pt = 0; pt < points; ++pt) {
        std::vector<double> row{roundSignificant(units::radToDeg(g.slipAngle(pt))), g.slip(pt)};
        for (std::size_t o = 0; o < outputs().size(); ++o) {
            const std::size_t column = o * points + pt;
            const auto c = static_cast<Eigen::Index>(column);
            for (std::size_t k = 0; k < params.size(); ++k) {
                const auto i = static_cast<Eigen::Index>(k);
                if (sobol) {
                    const gsa::SobolIndices& s = sobol->indices;
                    row.insert(row.end(), {s.first_order(i, c), s.first_order_conf(i, c),
                                           s.total(i, c), s.total_conf(i, c)});
                } else {
                    const gsa::MorrisIndices& m = morris->indices;
                    row.insert(row.end(),
                               {m.mu_star(i, c), m.mu_star_conf(i, c), m.mu(i, c), m.sigma(i, c)});
                }
            }
            row.push_back(static_cast<double>(sobol ? sobol->indices.samples_used[column]
                                                    : morris->indices.trajectories_used[column]));
        }
        for (double& v : row) v = v == 0.0 ? 0.0 : v;
        t.rows.push_back(std::move(row));
    }
    return t;
}

nlohmann::json GlobalSensitivityResult::toJson() const {
    static const char* const kStatus[] = {"completed", "cancelled", "too many failures"};
    const gsa::OperatingGrid& g = grid();
    std::vector<double> betas;
    for (double b : g.slip_angles_rad) betas.push_back(roundSignificant(units::radToDeg(b)));
    std::vector<std::string> names;
    for (gsa::Output o : outputs()) names.emplace_back(gsa::outputName(o));
    nlohmann::json j{{"method", sobol ? "sobol" : "morris"},
                     {"status", kStatus[static_cast<int>(status())]},
                     {"message", message()},
                     {"parameters", parameters()},
                     {"outputs", names},
                     {"slips", g.slips},
                     {"slip_angles_deg", betas},
                     {"evaluations", sobol ? sobol->evaluations : morris->evaluations}};
    if (status() == gsa::StudyStatus::kTooManyFailures) return j;
    auto add = [&](const char* key, const Eigen::MatrixXd& m) {
        nlohmann::json per_output = nlohmann::json::object();
        for (std::size_t o = 0; o < names.size(); ++o)
            per_output[names[o]] = matrixJson(outputBlock(m, o, g.size()));
        j[key] = std::move(per_output);
    };
    if (sobol) {
        j["base_samples"] = sobol->base_samples;
        add("S1", sobol->indices.first_order);
        add("ST", sobol->indices.total);
        add("S1_conf", sobol->indices.first_order_conf);
        add("ST_conf", sobol->indices.total_conf);
    } else {
        add("mu_star", morris->indices.mu_star);
        add("mu", morris->indices.mu);
        add("sigma", morris->indices.sigma);
        add("mu_star_conf", morris->indices.mu_star_conf);
    }
    return j;
}

GlobalSensitivityResult computeGlobalSensitivity(const Inputs& inputs,
                                                 const GlobalSensitivitySettings& s,
                                                 const Control& control) {
    // The reader's checks, in its words, for settings built in code (the panel's, Python's).
    std::vector<Issue> issues = io::fieldIssues(s);
    for (Issue& issue : globalSensitivityRuleIssues(s)) issues.push_back(std::move(issue));
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    const gsa::WheelStudy study = wheelStudyOf(inputs, s.study);
    gsa::BootstrapOptions bootstrap;
    bootstrap.resamples = s.resamples;
    bootstrap.confidence_level = s.confidence_level;
    bootstrap.seed = s.study.seed;
    const gsa::RunControl run = runControl(control, s.study.threads);
    GlobalSensitivityResult out;
    out.method = s.method;
    if (s.method == GsaMethod::kSobol) {
        gsa::SobolOptions options;
        options.base_samples = s.samples;
        options.seed = s.study.seed;
        options.bootstrap = bootstrap;
        options.max_failed_fraction = s.study.max_failed_fraction;
        out.sobol = gsa::sobolStudy(study, options, run);
    } else {
        gsa::MorrisOptions options;
        options.trajectories = s.samples;
        options.levels = s.levels;
        options.seed = s.study.seed;
        options.bootstrap = bootstrap;
        options.max_failed_fraction = s.study.max_failed_fraction;
        out.morris = gsa::morrisStudy(study, options, run);
    }
    return out;
}

Outcome globalSensitivityOutcome(GlobalSensitivityResult result) {
    Outcome out;
    out.status = statusOf(result.status());
    out.message = result.message();
    out.tables.push_back({"indices", "", result.table()});
    out.documents.push_back({"-indices.json", result.toJson()});
    if (!out.message.empty()) out.notes.push_back(out.message);
    out.result = std::move(result);
    return out;
}

AnalysisType globalSensitivityType() {
    return makeAnalysisType<GlobalSensitivitySettings>(
        "sensitivity-global",
        "Sobol' first-order and total indices with confidence intervals, or Morris screening, "
        "of chosen outputs at chosen slips over soil parameter ranges or distributions",
        {"indices"}, {{"indices", "-indices"}},
        [](io::ObjectReader& r, const ReadContext&, GlobalSensitivitySettings& s) {
            readGlobalSensitivitySettings(r, s);
        },
        [](const Inputs& in, const GlobalSensitivitySettings& s, const Control& c) {
            return computeGlobalSensitivity(in, s, c);
        },
        globalSensitivityOutcome);
}

StudyDefinition bandStudyDefaults() {
    StudyDefinition d;
    d.outputs = {"Fx_N", "Fs_N"};
    d.slips.clear();
    return d;
}

void readUncertaintyBandSettings(io::ObjectReader& r, UncertaintyBandSettings& out) {
    io::readFields(r, out);
    // No slips: 0 … the conditions' slip_max in slip_count points.
    for (Issue& issue : studyRuleIssues(out.study, false))
        r.report(issue.where, std::move(issue.message));
}

nlohmann::json toJson(const UncertaintyBandSettings& s) { return io::fieldsToJson(s); }

Table UncertaintyBandResult::table() const {
    Table t = bands.table();
    if (!bands.usable()) return t;
    for (std::size_t o = 0; o < bands.outputs.size(); ++o)
        t.columns.push_back(std::string(gsa::outputName(bands.outputs[o])) + "_nominal");
    for (std::size_t p = 0; p < t.rows.size(); ++p) {
        for (std::size_t o = 0; o < bands.outputs.size(); ++o)
            t.rows[p].push_back(
                nominal(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(p)));
    }
    return t;
}

UncertaintyBandResult computeUncertaintyBands(const Inputs& inputs,
                                              const UncertaintyBandSettings& s,
                                              const Control& control) {
    // The reader's checks, in its words, for settings built in code (the panel's, Python's).
    std::vector<Issue> issues = io::fieldIssues(s);
    for (Issue& issue : studyRuleIssues(s.study, false)) issues.push_back(std::move(issue));
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    StudyDefinition definition = s.study;
    if (definition.slips.empty())
        definition.slips = linspace(0.0, inputs.conditions.slip_max, s.slip_count);
    const gsa::WheelStudy study = wheelStudyOf(inputs, definition);
    gsa::BandOptions options;
    options.samples = s.samples;
    options.seed = definition.seed;
    options.percentiles = s.percentiles;
    options.max_failed_fraction = definition.max_failed_fraction;
    UncertaintyBandResult out;
    out.bands = gsa::uncertaintyBands(study, options, runControl(control, definition.threads));
    // The nominal curve: the inputs' soil itself, as one row of its own parameter values.
    const gsa::WheelTarget target(study);
    const std::vector<std::string>& names = study.parameters.names();
    Eigen::MatrixXd row(1, static_cast<Eigen::Index>(names.size()));
    for (std::size_t k = 0; k < names.size(); ++k) {
        row(0, static_cast<Eigen::Index>(k)) =
            soil::userValue(inputs.soil, *soil::findSoilField(names[k]));
    }
    gsa::RunControl one;
    one.threads = 1;
    const gsa::TargetValues values = target.evaluate(row, one);
    const auto outputs = static_cast<Eigen::Index>(study.outputs.size());
    const auto points = static_cast<Eigen::Index>(target.points());
    out.nominal.resize(outputs, points);
    for (Eigen::Index o = 0; o < outputs; ++o) {
        for (Eigen::Index p = 0; p < points; ++p) {
            const bool ok =
                values.status(0, p) == static_cast<std::uint8_t>(gsa::SampleStatus::kOk);
            out.nominal(o, p) =
                ok ? values.values(0, o * points + p) : std::numeric_limits<double>::quiet_NaN();
        }
    }
    return out;
}

Outcome uncertaintyBandOutcome(UncertaintyBandResult result) {
    Outcome out;
    out.status = statusOf(result.bands.status);
    out.message = result.bands.message;
    out.tables.push_back({"bands", "", result.table()});
    if (!out.message.empty()) out.notes.push_back(out.message);
    out.result = std::move(result);
    return out;
}

AnalysisType uncertaintyBandType() {
    return makeAnalysisType<UncertaintyBandSettings>(
        "uncertainty-bands",
        "Monte Carlo percentile bands of forces, moments or sinkage against slip when soil "
        "parameters are uncertain (ranges, normal distributions or a posterior)",
        {"bands"}, {{"bands", "-bands"}},
        [](io::ObjectReader& r, const ReadContext&, UncertaintyBandSettings& s) {
            readUncertaintyBandSettings(r, s);
        },
        [](const Inputs& in, const UncertaintyBandSettings& s, const Control& c) {
            return computeUncertaintyBands(in, s, c);
        },
        uncertaintyBandOutcome);
}

CorrelatedParameters correlatedFromIdentification(const identification::DecoupledParameters& p,
                                                  const identification::Uncertainty& u,
                                                  const soil::SoilParameters& base,
                                                  const wheel::WheelParameters& wheel) {
    using namespace identification;
    if (!u.computed) {
        throw std::invalid_argument("the identification has no covariance (rank deficient: " +
                                    (u.flags.empty()
                                         ? std::string("see its flags")
                                         : u.flags.front().worded(ParameterNaming::kKey)) +
                                    ")");
    }
    const soil::SoilParameters soil = identification::soilOf(base, wheel, p);
    CorrelatedParameters out;
    std::vector<std::size_t> used;
    std::vector<double> sd;
    for (std::size_t k = 0; k < kFullParameterCount; ++k) {
        if (!(u.std[k] > 0.0) || !std::isfinite(u.std[k])) continue;
        // The soil field carrying the refined parameter (K_s through k_φ, k_c fixed).
        const char* key = soilKeyOf(fieldOf(static_cast<FullParameter>(k)));
        const soil::SoilField& field = *soil::findSoilField(key);
        used.push_back(k);
        out.keys.emplace_back(key);
        out.mean.push_back(soil.*field.member / field.to_si);
        sd.push_back(u.std[k] / field.to_si);
    }
    if (used.empty()) throw std::invalid_argument("the identification has no standard deviations");
    for (std::size_t i = 0; i < used.size(); ++i) {
        std::vector<double> row;
        for (std::size_t j = 0; j < used.size(); ++j) {
            // ρ made exactly symmetric (the covariance's rounding leaves ρ_ij ≠ ρ_ji in the
            // last bit), so that a reader's symmetry check sees the matrix it is.
            const double rho =
                i == j ? 1.0
                       : 0.5 * (u.correlation[used[i]][used[j]] + u.correlation[used[j]][used[i]]);
            row.push_back(sd[i] * sd[j] * rho);
        }
        out.covariance.push_back(std::move(row));
    }
    return out;
}

}  // namespace terra::analysis
