#include "core/analysis/compaction.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/compaction/stress_at_depth.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"

namespace terra::analysis {
namespace {

// Depths this close to the deepest load are inside the discretised footprint's near field.
constexpr double kNearField = 1e-3;  // [m]

double stressFor(const compaction::StressMeasures& m, RiskStress which) {
    return which == RiskStress::kMajor ? m.major : m.sigma_z;
}

// Propagations of one footprint, one per ν in use.
class Propagations {
public:
    Propagations(std::vector<compaction::PointLoad> loads) : loads_(std::move(loads)) {}
    const compaction::StressPropagation& at(double nu) {
        auto it = cache_.find(nu);
        if (it == cache_.end())
            it = cache_.emplace(nu, compaction::StressPropagation(loads_, nu)).first;
        return it->second;
    }
    double deepest() const {
        double d = 0.0;
        for (const auto& l : loads_) d = std::max(d, l.position.z());
        return d;
    }
    double xMin() const {
        double x = 0.0;
        for (const auto& l : loads_) x = std::min(x, l.position.x());
        return x;
    }
    double xMax() const {
        double x = 0.0;
        for (const auto& l : loads_) x = std::max(x, l.position.x());
        return x;
    }

private:
    std::vector<compaction::PointLoad> loads_;
    std::map<double, compaction::StressPropagation> cache_;
};

double concentrationAt(const CompactionSettings& s, const soil::SoilProfile* profile, double z) {
    if (s.concentration) return *s.concentration;
    if (profile) {
        if (const soil::SoilLayer* layer = profile->layerAt(z); layer && layer->concentration)
            return *layer->concentration;
    }
    return kDefaultConcentration;
}

}  // namespace

std::vector<double> CompactionSettings::defaultDepths() {
    std::vector<double> out;
    for (int i = 0; i <= 18; ++i) out.push_back(roundSignificant(0.1 + 0.05 * i));
    return out;
}

const FieldInfo& reloadK0Field() {
    static const FieldInfo field{
        "reload_k0_kPa_m",
        "kPa/m",
        "k0",
        "reload stiffness k0",
        "k0 of the reload stiffness k_u = k0 + Au z_u of the repeated passes",
        {0.0, 1e9},
        1e3};
    return field;
}

const FieldInfo& reloadAuField() {
    static const FieldInfo field{
        "reload_Au_kPa_m2",
        "kPa/m2",
        "Au",
        "reload stiffness Au",
        "Au of the reload stiffness k_u = k0 + Au z_u of the repeated passes",
        {0.0, 1e12},
        1e3};
    return field;
}

void readProfileKey(io::ObjectReader& r, const char* key, std::optional<soil::SoilProfile>& out) {
    const nlohmann::json* profile = r.value(key);
    if (profile == nullptr || profile->is_string()) return;  // a name: readCompactionSettings
    if (!profile->is_object()) {
        r.report(key, "expected a profile object, a preset name or a path, got " +
                          io::describeJson(*profile));
        return;
    }
    io::ObjectReader p = r.object(key);
    out = io::readProfile(p);
    p.finish();
}

nlohmann::json writeProfileKey(const std::optional<soil::SoilProfile>& profile) {
    return profile ? io::toJson(*profile) : nlohmann::json();
}

void readMapPoints(io::ObjectReader& r, const char* key, CompactionSettings& out) {
    std::vector<double> map;
    if (r.numbers(key, map, Range{0.0, kMaxCompactionMapPoints}, {}, 2, 2)) {
        out.map_x_points = static_cast<int>(map[0]);
        out.map_z_points = static_cast<int>(map[1]);
    }
}

nlohmann::json writeMapPoints(const CompactionSettings& s) {
    return s.map_x_points > 0 ? nlohmann::json{s.map_x_points, s.map_z_points} : nlohmann::json();
}

void readMapPass(io::ObjectReader& r, const char* key, CompactionSettings& out) {
    r.integer(key, out.map_pass, 1, kMaxCompactionPasses);
}

nlohmann::json writeMapPass(const CompactionSettings& s) {
    return s.map_x_points > 0 ? nlohmann::json(s.map_pass) : nlohmann::json();
}

std::vector<Issue> compactionRuleIssues(const CompactionSettings& s) {
    std::vector<Issue> issues;
    if (s.depths_m.empty()) issues.push_back({"depths_m", "give at least one depth"});
    for (std::size_t i = 1; i < s.depths_m.size(); ++i) {
        if (!(s.depths_m[i] > s.depths_m[i - 1])) {
            issues.push_back({"depths_m", "depths must increase (" + formatNumber(s.depths_m[i]) +
                                              " after " + formatNumber(s.depths_m[i - 1]) + ")"});
            break;
        }
    }
    return issues;
}

std::vector<Issue> compactionRunIssues(const CompactionSettings& s) {
    std::vector<Issue> issues;
    if (!(s.reload.k0_pa_m + s.reload.au_pa_m2 > 0.0)) {
        issues.push_back({"reload_k0_kPa_m",
                          "the reload stiffness k0 + Au z must be > 0: give "
                          "k0 > 0 or Au > 0"});
    }
    const bool map = s.map_x_points != 0 || s.map_z_points != 0;
    if (map &&
        (s.map_x_points < 2 || s.map_z_points < 2 || s.map_x_points > kMaxCompactionMapPoints ||
         s.map_z_points > kMaxCompactionMapPoints)) {
        issues.push_back({"map_points", std::to_string(s.map_x_points) + " x " +
                                            std::to_string(s.map_z_points) +
                                            ": each count in [2, 1000], or both 0 (no map)"});
    }
    if (map && (s.map_pass < 1 || s.map_pass > s.passes)) {
        issues.push_back({"map_pass", std::to_string(s.map_pass) + " is outside [1, passes = " +
                                          std::to_string(s.passes) + "]"});
    }
    return issues;
}

void readCompactionSettings(io::ObjectReader& r, CompactionSettings& out,
                            const io::PresetLocations* locations,
                            const std::filesystem::path& base_dir) {
    io::readFields(r, out);
    // A profile by preset name or path: found where the caller's presets are.
    if (const nlohmann::json* profile = r.has("profile") ? r.value("profile") : nullptr;
        profile != nullptr && profile->is_string()) {
        std::string name = profile->get<std::string>();
        std::filesystem::path path(name);
        if (path.has_parent_path() && path.is_relative() && !base_dir.empty())
            name = (base_dir / path).string();
        Result<soil::SoilProfile> read =
            locations ? io::resolveProfile(*locations, name) : io::loadProfile(name);
        if (read) {
            out.profile = read.value();
        } else {
            for (const Issue& issue : read.issues())
                r.report("profile", issue.where + ": " + issue.message);
        }
    }
    for (Issue& issue : compactionRuleIssues(out)) r.report(issue.where, std::move(issue.message));
}

nlohmann::json toJson(const CompactionSettings& s) { return io::fieldsToJson(s); }

CompactionResult computeCompaction(const Inputs& in, const CompactionSettings& s,
                                   const Control& control) {
    // The reader's checks, in its words, for settings built in code (a panel's, Python's).
    std::vector<Issue> issues = io::fieldIssues(s);
    for (Issue& issue : compactionRuleIssues(s)) issues.push_back(std::move(issue));
    for (Issue& issue : compactionRunIssues(s)) issues.push_back(std::move(issue));
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    const contact::ContactParameters<double> untouched = in.contact();
    CompactionResult out;
    out.load_n = in.conditions.load_n;
    if (s.profile) {
        out.profile = s.profile;
    } else if (in.soil.profile) {
        if (std::vector<Issue> issues = soil::validate(*in.soil.profile, "soil.profile");
            !issues.empty())
            throw std::invalid_argument(formatIssues(issues));
        out.profile = in.soil.profile;
    }
    const soil::SoilProfile* profile = out.profile ? &*out.profile : nullptr;
    if (profile && profile->layers.back().bottom_m < s.depths_m.back()) {
        out.notes.push_back("the profile ends at " + formatNumber(profile->layers.back().bottom_m) +
                            " m: deeper depths have no sigma_pc and no risk");
    }
    out.concentration_used = s.concentration.value_or(kDefaultConcentration);
    const compaction::RiskMeasure measure = s.risk_stress == RiskStress::kMajor
                                                ? compaction::RiskMeasure::kMajor
                                                : compaction::RiskMeasure::kVertical;
    // The layers' state as the passes change it (σ_pc made explicit: it only grows).
    std::vector<soil::SoilLayer> layers =
        profile ? profile->layers : std::vector<soil::SoilLayer>{};
    for (soil::SoilLayer& layer : layers)
        layer.precompression_pa = soil::precompressionStress(layer);

    compaction::PassConditions conditions;
    conditions.load_n = in.conditions.load_n;
    conditions.slip = s.slip;
    conditions.slip_angle_rad = units::degToRad(s.slip_angle_deg);
    conditions.exit = s.model.exit;
    conditions.max_stress_angle_rad = s.model.max_stress_angle_rad;
    conditions.bulldozing = s.model.bulldozing;
    conditions.model = in.conditions.model();
    compaction::FootprintOptions footprint_options;
    footprint_options.width = s.width;
    compaction::TrackMemory memory;
    out.envelope.resize(s.depths_m.size());
    for (std::size_t d = 0; d < s.depths_m.size(); ++d) {
        out.envelope[d].depth_m = s.depths_m[d];
        if (const int li = compaction::layerIndex(layers, s.depths_m[d]); li >= 0)
            out.envelope[d].precompression_pa =
                *layers[static_cast<std::size_t>(li)].precompression_pa;
    }
    std::vector<bool> reached(s.depths_m.size(), false);
    for (int k = 1; k <= s.passes; ++k) {
        if (control.cancelled()) {
            out.cancelled = true;
            out.message = "cancelled after " + std::to_string(k - 1) + " of " +
                          std::to_string(s.passes) + " passes";
            break;
        }
        const compaction::SolvedPass solved =
            compaction::solvePass(untouched, memory, s.reload, conditions);
        if (!solved.ok) {
            out.message = "pass " + std::to_string(k) + ": " + solved.message;
            break;
        }
        if (!solved.warning.empty())
            out.notes.push_back("pass " + std::to_string(k) + ": " + solved.warning);
        CompactionPass pass;
        pass.pass = k;
        pass.entry_angle_deg = roundSignificant(units::radToDeg(solved.op.entry_angle_rad));
        pass.forces = solved.forces;
        pass.sinkage_m = solved.sinkage_m;
        pass.sinkage_increment_m = solved.sinkage_m - memory.max_sinkage_m;

        Propagations propagations(
            compaction::wheelFootprint(solved.params, solved.op, footprint_options));
        const double deepest = propagations.deepest();
        auto propagationAt = [&](double z) -> const compaction::StressPropagation& {
            return propagations.at(concentrationAt(s, profile, z));
        };
        for (std::size_t d = 0; d < s.depths_m.size(); ++d) {
            const double z = s.depths_m[d];
            if (!(z > deepest + kNearField)) continue;  // inside the rut or the wheel (noted)
            DepthValues v;
            v.depth_m = z;
            v.max = compaction::passMaxima(propagationAt(z), 0.0, z).maxima;
            if (const int li = compaction::layerIndex(layers, z); li >= 0) {
                v.precompression_pa = *layers[static_cast<std::size_t>(li)].precompression_pa;
                v.risk = riskOf(stressFor(v.max, s.risk_stress), *v.precompression_pa);
            }
            reached[d] = true;
            DepthValues& e = out.envelope[d];
            e.max.sigma_z = std::max(e.max.sigma_z, v.max.sigma_z);
            e.max.sigma_x = std::max(e.max.sigma_x, v.max.sigma_x);
            e.max.sigma_y = std::max(e.max.sigma_y, v.max.sigma_y);
            e.max.mean = std::max(e.max.mean, v.max.mean);
            e.max.major = std::max(e.max.major, v.max.major);
            if (v.risk && (!e.risk || static_cast<int>(*v.risk) > static_cast<int>(*e.risk)))
                e.risk = v.risk;
            pass.profile.push_back(v);
        }
        if (!layers.empty()) {
            bool deepest_is_red = false;
            pass.red_to_depth_m = compaction::redZoneDepth(s.depths_m, layers, propagationAt,
                                                           measure, deepest, &deepest_is_red);
            if (deepest_is_red) {
                out.notes.push_back("pass " + std::to_string(k) + ": red at the deepest depth (" +
                                    formatNumber(s.depths_m.back()) + " m); give deeper depths");
            }
            if (!out.red_to_depth_m || *pass.red_to_depth_m > *out.red_to_depth_m)
                out.red_to_depth_m = pass.red_to_depth_m;
            // Each layer compacts under the stress at its mid-depth (just below the rut when its
            // middle is inside it).
            for (soil::SoilLayer& layer : layers) {
                const double z = std::max(0.5 * (layer.top_m + layer.bottom_m), deepest + 0.01);
                if (z <= layer.bottom_m) {
                    const compaction::StressMeasures m =
                        compaction::passMaxima(propagationAt(z), 0.0, z).maxima;
                    const double compared = stressFor(m, s.risk_stress);
                    // K2: a published N works on p (O'Sullivan); a derived one on the risk's
                    // stress.
                    const bool published = layer.compression && layer.compression->virgin_n;
                    layer.bulk_density_kg_m3 =
                        soil::compactedDensity(layer, published ? m.mean : compared);
                    layer.precompression_pa = std::max(*layer.precompression_pa, compared);
                }
                pass.bulk_density_kg_m3.push_back(layer.bulk_density_kg_m3);
                pass.precompression_pa.push_back(*layer.precompression_pa);
            }
        }
        if (k == s.map_pass && s.map_x_points > 0) {
            out.map.columns = {"x_m", "z_m", "sigma_z_kPa", "p_kPa", "sigma_1_kPa"};
            const double z_hi = s.depths_m.back();
            const double z_lo = deepest + std::max(0.02 * z_hi, 0.005);
            const double x_lo = propagations.xMin() - z_hi, x_hi = propagations.xMax() + z_hi;
            for (int iz = 0; iz < s.map_z_points; ++iz) {
                const double z = z_lo + (z_hi - z_lo) * iz / (s.map_z_points - 1);
                const compaction::StressPropagation& prop = propagationAt(z);
                for (int ix = 0; ix < s.map_x_points; ++ix) {
                    const double x = x_lo + (x_hi - x_lo) * ix / (s.map_x_points - 1);
                    const compaction::StressMeasures m = prop.measuresAt({x, 0.0, z});
                    out.map.rows.push_back({x, z, m.sigma_z / 1e3, m.mean / 1e3, m.major / 1e3});
                }
            }
        }
        memory = compaction::rememberPass(memory, s.reload, untouched, conditions, solved);
        pass.rut_depth_m = memory.rut_depth_m;
        out.passes.push_back(std::move(pass));
        control.report(static_cast<double>(k) / s.passes);
    }
    std::size_t left_out = 0;
    std::vector<DepthValues> envelope;
    for (std::size_t d = 0; d < s.depths_m.size(); ++d) {
        if (reached[d])
            envelope.push_back(out.envelope[d]);
        else
            ++left_out;
    }
    if (!out.passes.empty() && left_out > 0) {
        out.notes.push_back(std::to_string(left_out) +
                            " depths lie inside the rut or the wheel (above " +
                            formatNumber(roundSignificant(out.passes.front().sinkage_m, 4)) +
                            " m) and are left out");
    }
    out.envelope = std::move(envelope);
    return out;
}

nlohmann::json toJson(const CompactionResult& r) {
    using nlohmann::json;
    auto profileJson = [](const std::vector<DepthValues>& rows) {
        json out = json::array();
        for (const DepthValues& v : rows) {
            json row{{"depth_m", v.depth_m},
                     {"sigma_z_kPa", v.max.sigma_z / 1e3},
                     {"sigma_x_kPa", v.max.sigma_x / 1e3},
                     {"sigma_y_kPa", v.max.sigma_y / 1e3},
                     {"p_kPa", v.max.mean / 1e3},
                     {"sigma_1_kPa", v.max.major / 1e3}};
            if (v.precompression_pa) row["sigma_pc_kPa"] = *v.precompression_pa / 1e3;
            if (v.risk) row["risk"] = riskName(*v.risk);
            out.push_back(row);
        }
        return out;
    };
    json out{{"load_N", r.load_n}, {"profile", profileJson(r.envelope)}};
    if (r.red_to_depth_m) out["red_to_depth_m"] = *r.red_to_depth_m;
    json passes = json::array();
    for (const CompactionPass& p : r.passes) {
        json pass{
            {"pass", p.pass},
            {"entry_angle_deg", p.entry_angle_deg},
            {"sinkage_m", p.sinkage_m},
            {"sinkage_increment_m", p.sinkage_increment_m},
            {"rut_depth_m", p.rut_depth_m},
            {"Fx_N", p.forces.fx},
            {"Fz_N", p.forces.fz},
            {"My_Nm", p.forces.my},
            {"max_sigma_z_kPa", p.profile.empty() ? 0.0 : p.profile.front().max.sigma_z / 1e3},
            {"profile", profileJson(p.profile)}};
        if (p.red_to_depth_m) pass["red_to_depth_m"] = *p.red_to_depth_m;
        if (r.profile) {
            json density = json::array(), pc = json::array();
            for (double v : p.bulk_density_kg_m3) density.push_back(v / 1e3);
            for (double v : p.precompression_pa) pc.push_back(v / 1e3);
            pass["bulk_density_Mg_m3"] = density;
            pass["sigma_pc_kPa"] = pc;
        }
        passes.push_back(pass);
    }
    out["passes"] = passes;
    if (r.profile) out["soil_profile"] = io::toJson(*r.profile);
    out["status"] = statusName(r.status());
    if (!r.message.empty()) out["message"] = r.message;
    out["notes"] = r.notes;
    return out;
}

Summary compactionSummary(const Inputs& in, const CompactionSettings& s,
                          const CompactionResult& r) {
    using Emphasis = SummaryRow::Emphasis;
    Summary out;
    const std::string nu = s.concentration ? formatNumber(*s.concentration)
                           : r.profile     ? std::string("per layer")
                                           : formatNumber(kDefaultConcentration);
    out.push_back({"compaction",
                   in.soil.name + ", " + in.wheel.name + ", W = " + formatNumber(r.load_n) +
                       " N, s = " + formatNumber(s.slip) +
                       ", beta = " + formatNumber(s.slip_angle_deg) + " deg, nu = " + nu + ", " +
                       std::to_string(s.passes) + (s.passes == 1 ? " pass" : " passes"),
                   "", "", Emphasis::kHeading, ""});
    if (!r.ok()) {
        out.push_back({statusName(r.status()), r.message, "",
                       r.passes.empty() ? "" : "the passes before are kept", Emphasis::kWarning,
                       "/message"});
    }
    if (r.profile) {
        out.push_back({"profile", r.profile->name, "",
                       std::to_string(r.profile->layers.size()) + " layers", Emphasis::kNormal,
                       "/soil_profile/name"});
    } else {
        out.push_back({"profile", "none", "", "no sigma_pc, no risk", Emphasis::kNormal, ""});
    }
    if (!r.passes.empty()) {
        const CompactionPass& last = r.passes.back();
        const std::string at = "/passes/" + std::to_string(r.passes.size() - 1);
        const std::string pass = std::to_string(last.pass);
        out.push_back({"rut after pass " + pass, formatFixed(last.rut_depth_m * 1e3, 3), "mm", "",
                       Emphasis::kNormal, at + "/rut_depth_m", last.rut_depth_m});
        out.push_back({"sinkage in pass " + pass, formatFixed(last.sinkage_m * 1e3, 3), "mm", "",
                       Emphasis::kNormal, at + "/sinkage_m", last.sinkage_m});
    }
    if (r.red_to_depth_m && *r.red_to_depth_m > 0.0) {
        out.push_back({"red zone down to", formatFixed(*r.red_to_depth_m, 3), "m",
                       "stress > 1.1 sigma_pc", Emphasis::kWarning, "/red_to_depth_m",
                       *r.red_to_depth_m});
    } else if (r.red_to_depth_m) {
        out.push_back({"red zone", "none", "", "stress <= 1.1 sigma_pc at every depth",
                       Emphasis::kNormal, "/red_to_depth_m", *r.red_to_depth_m});
    }
    if (r.profile && !r.passes.empty() &&
        r.passes.back().bulk_density_kg_m3.size() == r.profile->layers.size()) {
        const CompactionPass& last = r.passes.back();
        const std::string at = "/passes/" + std::to_string(r.passes.size() - 1);
        out.push_back({"bulk density after pass " + std::to_string(last.pass), "", "", "",
                       Emphasis::kHeading, at});
        for (std::size_t l = 0; l < r.profile->layers.size(); ++l) {
            const soil::SoilLayer& layer = r.profile->layers[l];
            const double before = layer.bulk_density_kg_m3 / 1e3;
            const double after = last.bulk_density_kg_m3[l] / 1e3;
            SummaryRow row{formatNumber(layer.top_m) + "-" + formatNumber(layer.bottom_m) + " m",
                           formatFixed(after, 3),
                           "Mg/m3",
                           "unchanged",
                           Emphasis::kNormal,
                           at + "/bulk_density_Mg_m3/" + std::to_string(l),
                           after};
            if (std::abs(after - before) >= kDensityShownMg_m3) {
                const double change = 100.0 * (after - before) / before;
                row.detail = "from " + formatFixed(before, 3) + ", " + (change > 0 ? "+" : "") +
                             formatFixed(change, 2) + " %";
            }
            out.push_back(std::move(row));
        }
    }
    for (std::size_t n = 0; n < r.notes.size(); ++n) {
        out.push_back(
            {"note", r.notes[n], "", "", Emphasis::kWarning, "/notes/" + std::to_string(n)});
    }
    return out;
}

Outcome compactionOutcome(CompactionResult result) {
    Outcome out;
    Table profile{{"depth_m", "sigma_z_kPa", "sigma_x_kPa", "sigma_y_kPa", "p_kPa", "sigma_1_kPa",
                   "sigma_pc_kPa", "risk_level"},
                  {}};
    for (const DepthValues& v : result.envelope) {
        profile.rows.push_back({v.depth_m, v.max.sigma_z / 1e3, v.max.sigma_x / 1e3,
                                v.max.sigma_y / 1e3, v.max.mean / 1e3, v.max.major / 1e3,
                                v.precompression_pa ? *v.precompression_pa / 1e3 : 0.0,
                                v.risk ? static_cast<double>(*v.risk) : -1.0});
    }
    Table passes{{"pass", "sinkage_m", "sinkage_increment_m", "rut_depth_m", "Fx_N", "Fz_N",
                  "My_Nm", "max_sigma_z_kPa", "red_to_depth_m"},
                 {}};
    const std::size_t layer_count = result.profile ? result.profile->layers.size() : 0;
    for (std::size_t l = 0; l < layer_count; ++l)
        passes.columns.push_back("bulk_density_" + std::to_string(l + 1) + "_Mg_m3");
    for (const CompactionPass& p : result.passes) {
        std::vector<double> row{static_cast<double>(p.pass),
                                p.sinkage_m,
                                p.sinkage_increment_m,
                                p.rut_depth_m,
                                p.forces.fx,
                                p.forces.fz,
                                p.forces.my,
                                p.profile.empty() ? 0.0 : p.profile.front().max.sigma_z / 1e3,
                                p.red_to_depth_m.value_or(0.0)};
        for (std::size_t l = 0; l < layer_count; ++l)
            row.push_back(l < p.bulk_density_kg_m3.size() ? p.bulk_density_kg_m3[l] / 1e3 : 0.0);
        passes.rows.push_back(std::move(row));
    }
    out.tables.push_back({"profile", "", std::move(profile)});
    out.tables.push_back({"passes", "-passes", std::move(passes)});
    if (!result.map.rows.empty()) out.tables.push_back({"map", "-map", result.map});
    out.notes = result.notes;
    if (!result.ok()) {
        out.status = result.cancelled ? Outcome::Status::kCancelled : Outcome::Status::kFailed;
        out.message = result.message;
    }
    out.documents.push_back({".json", toJson(result)});
    out.result = std::move(result);
    return out;
}

AnalysisType compactionType() {
    return makeAnalysisType<CompactionSettings>(
        "compaction",
        "stress at depth under the wheel, compaction risk against the profile's precompression "
        "stress, and repeated passes on one track (docs/compaction.md)",
        {"profile", "passes", "map"}, {{"profile", ""}, {"passes", "-passes"}, {"map", "-map"}},
        [](io::ObjectReader& r, const ReadContext& context, CompactionSettings& s) {
            readCompactionSettings(r, s, context.locations, context.base_dir);
        },
        [](const Inputs& in, const CompactionSettings& s, const Control& c) {
            return computeCompaction(in, s, c);
        },
        compactionOutcome);
}

}  // namespace terra::analysis
