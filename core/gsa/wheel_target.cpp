#include "core/gsa/wheel_target.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"

namespace terra::gsa {
namespace {

constexpr const char* kOutputNames[] = {"Fx_N",           "Fy_N",
                                        "Fz_N",           "Mx_Nm",
                                        "My_Nm",          "Mz_Nm",
                                        "Fb_N",           "Fs_N",
                                        "sinkage_m",      "entry_angle_deg",
                                        "exit_angle_deg", "max_sigma_z_kPa",
                                        "red_to_depth_m", "rut_depth_m"};

std::string unitSuffix(const soil::SoilField& field) {
    return std::string(field.unit) == "-" ? "" : std::string(" ") + field.unit;
}

// The finite bounds of a parameter's distribution must be values the field allows.
void checkBound(std::vector<Issue>& issues, const std::string& name, const soil::SoilField& field,
                const char* what, double low, double high) {
    for (double v : {low, high}) {
        if (std::isinf(v) || field.range.contains(v)) continue;
        issues.push_back({"parameters." + name,
                          std::string(what) + " [" + formatNumber(low) + ", " + formatNumber(high) +
                              "] reaches " + formatNumber(v) + ", outside the allowed range " +
                              field.range.describe() + unitSuffix(field)});
        return;
    }
}

// The compaction outputs of one sample (docs/compaction.md): `passes` wheels on one track; the
// largest σ_z at the depth and the deepest red zone over the passes, the rut after them.
struct CompactionValues {
    bool ok = false;
    double max_sigma_z_kpa = 0.0;
    double red_depth_m = 0.0;
    double rut_m = 0.0;
};

CompactionValues evaluateCompaction(const contact::ContactParameters<double>& untouched,
                                    const compaction::PassConditions& conditions,
                                    const CompactionStudy& study,
                                    const std::vector<soil::SoilLayer>& initial_layers,
                                    bool stresses, bool red) {
    CompactionValues out;
    std::vector<soil::SoilLayer> layers = initial_layers;
    compaction::TrackMemory memory;
    const compaction::FootprintOptions footprint;
    for (int k = 1; k <= study.passes; ++k) {
        const compaction::SolvedPass pass =
            compaction::solvePass(untouched, memory, study.reload, conditions);
        if (!pass.ok) return out;
        if (stresses || red) {
            const std::vector<compaction::PointLoad> loads =
                compaction::wheelFootprint(pass.params, pass.op, footprint);
            double deepest = 0.0;
            for (const compaction::PointLoad& l : loads)
                deepest = std::max(deepest, l.position.z());
            std::map<double, compaction::StressPropagation> cache;
            auto propagationAt = [&](double z) -> const compaction::StressPropagation& {
                double nu = 5.0;
                if (study.concentration) {
                    nu = *study.concentration;
                } else if (const int i = compaction::layerIndex(layers, z);
                           i >= 0 && layers[static_cast<std::size_t>(i)].concentration) {
                    nu = *layers[static_cast<std::size_t>(i)].concentration;
                }
                auto it = cache.find(nu);
                if (it == cache.end())
                    it = cache.emplace(nu, compaction::StressPropagation(loads, nu)).first;
                return it->second;
            };
            if (stresses && study.depth_m > deepest + 1e-3) {
                out.max_sigma_z_kpa =
                    std::max(out.max_sigma_z_kpa,
                             compaction::passStress(propagationAt(study.depth_m), study.depth_m,
                                                    compaction::RiskMeasure::kVertical) /
                                 1e3);
            }
            if (red) {
                out.red_depth_m =
                    std::max(out.red_depth_m,
                             compaction::redZoneDepth(study.red_scan_depths, layers, propagationAt,
                                                      study.measure, deepest));
                // The layers compact (K1–K3) before the next pass, as the analysis does.
                for (soil::SoilLayer& layer : layers) {
                    const double z = std::max(0.5 * (layer.top_m + layer.bottom_m), deepest + 0.01);
                    if (z > layer.bottom_m || k == study.passes) continue;
                    const compaction::StressMeasures m =
                        compaction::passMaxima(propagationAt(z), 0.0, z).maxima;
                    const double compared =
                        study.measure == compaction::RiskMeasure::kMajor ? m.major : m.sigma_z;
                    const bool published = layer.compression && layer.compression->virgin_n;
                    layer.bulk_density_kg_m3 =
                        soil::compactedDensity(layer, published ? m.mean : compared);
                    layer.precompression_pa = std::max(*layer.precompression_pa, compared);
                }
            }
        }
        memory = compaction::rememberPass(memory, study.reload, untouched, conditions, pass);
    }
    out.rut_m = memory.rut_depth_m;
    out.ok = true;
    return out;
}

}  // namespace

bool isCompactionOutput(Output output) {
    return output == Output::kMaxSigmaZ || output == Output::kRedDepth ||
           output == Output::kRutDepth;
}

const char* outputName(Output output) { return kOutputNames[static_cast<int>(output)]; }

std::optional<Output> findOutput(std::string_view name) {
    for (int i = 0; i < static_cast<int>(std::size(kOutputNames)); ++i) {
        if (name == kOutputNames[i]) return static_cast<Output>(i);
    }
    return std::nullopt;
}

const std::vector<std::string>& outputNames() {
    static const std::vector<std::string> names(std::begin(kOutputNames), std::end(kOutputNames));
    return names;
}

void requireValid(const WheelStudy& study) {
    std::vector<Issue> issues = soil::validate(study.soil, "soil.");
    for (Issue& issue : wheel::validate(study.wheel, "wheel.")) issues.push_back(std::move(issue));
    const OperatingGrid& grid = study.grid;
    if (grid.slips.empty()) issues.push_back({"slips", "no slip values"});
    if (grid.slip_angles_rad.empty()) issues.push_back({"slip_angles", "no slip angles"});
    auto check = [&](const FieldInfo& field, double value) {
        checkRange(issues, field.key, value, field.range, field.displayUnit());
    };
    for (double s : grid.slips) check(contact::slipField(), s);
    for (double b : grid.slip_angles_rad) check(contact::slipAngleField(), roundedDegrees(b));
    if (grid.load_n) {
        check(contact::loadField(), *grid.load_n);
    } else {
        check(contact::entryAngleField(), roundedDegrees(grid.entry_angle_rad));
    }
    if (study.outputs.empty()) issues.push_back({"outputs", "no output to study"});
    for (std::size_t i = 0; i < study.outputs.size(); ++i) {
        if (std::find(study.outputs.begin(), study.outputs.begin() + i, study.outputs[i]) !=
            study.outputs.begin() + i) {
            issues.push_back(
                {"outputs", std::string(outputName(study.outputs[i])) + " is given twice"});
        }
    }
    const ParameterSpace& space = study.parameters;
    if (space.dimension() == 0) issues.push_back({"parameters", "no parameter to vary"});
    for (std::size_t i = 0; i < space.dimension(); ++i) {
        const std::string& name = space.names()[i];
        const soil::SoilField* field = soil::findSoilField(name);
        if (!field) {
            std::string keys;
            for (const soil::SoilField& f : soil::soilFields()) keys += std::string(" ") + f.key;
            issues.push_back({"parameters." + name, "is not a soil field (fields:" + keys + ")"});
            continue;
        }
        const Marginal* marginal = space.marginal(i);
        if (!marginal) continue;  // correlated normal: out-of-range samples are flagged
        if (const auto* u = std::get_if<Uniform>(marginal)) {
            checkBound(issues, name, *field, "the range", u->low, u->high);
        } else {
            const Normal& n = std::get<Normal>(*marginal);
            checkBound(issues, name, *field, "the truncation", n.low, n.high);
        }
    }
    const bool compaction_outputs =
        std::any_of(study.outputs.begin(), study.outputs.end(), isCompactionOutput);
    if (compaction_outputs) {
        const CompactionStudy& c = study.compaction;
        if (!grid.load_n) {
            issues.push_back({"entry_angle_deg",
                              "the compaction outputs need a load (the wheel "
                              "sinks into the rut of the passes before it)"});
        }
        checkRange(issues, "compaction.depth_m", c.depth_m, Range{0.0, 10.0, true}, "m");
        if (c.passes < 1 || c.passes > 100) {
            issues.push_back(
                {"compaction.passes", std::to_string(c.passes) + " is outside [1, 100]"});
        }
        if (c.concentration)
            checkRange(issues, "compaction.concentration", *c.concentration, Range{2.5, 12.0});
        const bool red = std::find(study.outputs.begin(), study.outputs.end(), Output::kRedDepth) !=
                         study.outputs.end();
        const std::optional<soil::SoilProfile>& profile =
            c.profile ? c.profile : study.soil.profile;
        if (red && !profile) {
            issues.push_back({"outputs",
                              "red_to_depth_m needs a soil profile (the soil file's "
                              "\"profile\", or the study's)"});
        }
        if (profile) {
            for (Issue& issue : soil::validate(*profile)) issues.push_back(std::move(issue));
        }
    }
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    requireValid(study.model);
    (void)contact::makeContactParameters(study.soil, study.wheel);  // K_s > 0
}

TargetValues concatenate(const std::vector<TargetValues>& chunks) {
    TargetValues out;
    Eigen::Index rows = 0, columns = 0, points = 0;
    for (const TargetValues& c : chunks) {
        if (c.values.rows() == 0) continue;
        if (rows > 0 && (c.values.cols() != columns || c.status.cols() != points)) {
            throw std::invalid_argument("concatenate: chunks of different widths");
        }
        rows += c.values.rows(), columns = c.values.cols(), points = c.status.cols();
    }
    out.values.resize(rows, columns);
    out.status.resize(rows, points);
    Eigen::Index at = 0;
    for (const TargetValues& c : chunks) {
        if (c.values.rows() == 0) continue;
        out.values.middleRows(at, c.values.rows()) = c.values;
        out.status.middleRows(at, c.status.rows()) = c.status;
        at += c.values.rows();
        out.cancelled = out.cancelled || c.cancelled;
    }
    return out;
}

WheelTarget::WheelTarget(WheelStudy study) : study_(std::move(study)) { requireValid(study_); }

TargetValues WheelTarget::evaluate(const Eigen::MatrixXd& rows, const RunControl& control) const {
    const std::size_t d = parameters(), points = this->points();
    if (static_cast<std::size_t>(rows.cols()) != d) {
        throw std::invalid_argument("WheelTarget::evaluate: rows have " +
                                    std::to_string(rows.cols()) + " columns, the study " +
                                    std::to_string(d) + " parameters");
    }
    const auto r_count = static_cast<std::size_t>(rows.rows());
    const std::size_t n = r_count * points;
    // Sample r · points + p is row r at grid point p.
    std::vector<double> slip(n), beta(n);
    std::vector<std::vector<double>> soil(d, std::vector<double>(n));
    for (std::size_t r = 0; r < r_count; ++r) {
        for (std::size_t p = 0; p < points; ++p) {
            const std::size_t i = r * points + p;
            slip[i] = study_.grid.slip(p), beta[i] = study_.grid.slipAngle(p);
            for (std::size_t k = 0; k < d; ++k) {
                soil[k][i] = rows(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
            }
        }
    }
    const double load = study_.grid.load_n.value_or(0.0);
    const double entry = study_.grid.entry_angle_rad;
    BatchInput input{n, slip, beta, {}, {}, {}};
    if (study_.grid.load_n) {
        input.load_n = std::span<const double>(&load, 1);
    } else {
        input.entry_angle_rad = std::span<const double>(&entry, 1);
    }
    for (std::size_t k = 0; k < d; ++k)
        input.soil.push_back({study_.parameters.names()[k], soil[k]});
    // Only the studied outputs are written.
    std::vector<std::vector<double>> buffers(study_.outputs.size(), std::vector<double>(n));
    std::vector<SampleStatus> status(n, SampleStatus::kNotEvaluated);
    BatchOutputView view;
    view.status = status;
    for (std::size_t o = 0; o < study_.outputs.size(); ++o) {
        std::span<double> b = buffers[o];
        switch (study_.outputs[o]) {
            case Output::kFx:
                view.fx_n = b;
                break;
            case Output::kFy:
                view.fy_n = b;
                break;
            case Output::kFz:
                view.fz_n = b;
                break;
            case Output::kMx:
                view.mx_nm = b;
                break;
            case Output::kMy:
                view.my_nm = b;
                break;
            case Output::kMz:
                view.mz_nm = b;
                break;
            case Output::kFb:
                view.fb_n = b;
                break;
            case Output::kFs:
                view.fs_n = b;
                break;
            case Output::kSinkage:
                view.sinkage_m = b;
                break;
            case Output::kEntryAngle:
                view.entry_angle_rad = b;
                break;
            case Output::kExitAngle:
                view.exit_angle_rad = b;
                break;
            case Output::kMaxSigmaZ:
            case Output::kRedDepth:
            case Output::kRutDepth:
                break;  // per sample below
        }
    }
    // With compaction outputs the batch (the first pass's status) is the first 10 % of the work.
    const bool compaction_outputs =
        std::any_of(study_.outputs.begin(), study_.outputs.end(), isCompactionOutput);
    RunControl batch_control = control, compaction_control = control;
    if (compaction_outputs && control.progress) {
        batch_control.progress = [&](double f) { control.progress(0.1 * f); };
        compaction_control.progress = [&](double f) { control.progress(0.1 + 0.9 * f); };
    }
    const BatchSummary summary = evaluateBatch(study_.soil, study_.wheel, input, study_.model, view,
                                               batch_control, InvalidSoil::kFlag);
    evaluateCompactionOutputs(input, buffers, status, compaction_control);
    TargetValues out;
    out.values.resize(static_cast<Eigen::Index>(r_count), static_cast<Eigen::Index>(columns()));
    out.status.resize(static_cast<Eigen::Index>(r_count), static_cast<Eigen::Index>(points));
    out.cancelled = summary.cancelled || std::find(status.begin(), status.end(),
                                                   SampleStatus::kNotEvaluated) != status.end();
    for (std::size_t o = 0; o < study_.outputs.size(); ++o) {
        const Output output = study_.outputs[o];
        const bool angle = output == Output::kEntryAngle || output == Output::kExitAngle;
        for (std::size_t r = 0; r < r_count; ++r) {
            for (std::size_t p = 0; p < points; ++p) {
                const double v = buffers[o][r * points + p];
                out.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(column(o, p))) =
                    angle ? units::radToDeg(v) : v;
            }
        }
    }
    for (std::size_t r = 0; r < r_count; ++r) {
        for (std::size_t p = 0; p < points; ++p) {
            out.status(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(p)) =
                static_cast<std::uint8_t>(status[r * points + p]);
        }
    }
    return out;
}

void WheelTarget::evaluateCompactionOutputs(const BatchInput& input,
                                            std::vector<std::vector<double>>& buffers,
                                            std::vector<SampleStatus>& status,
                                            const RunControl& control) const {
    std::vector<std::size_t> slots;  // (output index) of each compaction output
    for (std::size_t o = 0; o < study_.outputs.size(); ++o)
        if (isCompactionOutput(study_.outputs[o])) slots.push_back(o);
    if (slots.empty()) return;
    auto wants = [&](Output which) {
        return std::find(study_.outputs.begin(), study_.outputs.end(), which) !=
               study_.outputs.end();
    };
    const bool stresses = wants(Output::kMaxSigmaZ), red = wants(Output::kRedDepth);
    const CompactionStudy& c = study_.compaction;
    const std::optional<soil::SoilProfile>& profile = c.profile ? c.profile : study_.soil.profile;
    std::vector<soil::SoilLayer> layers =
        profile ? profile->layers : std::vector<soil::SoilLayer>{};
    for (soil::SoilLayer& layer : layers)
        layer.precompression_pa = soil::precompressionStress(layer);
    std::vector<const soil::SoilField*> fields;
    for (const SoilOverride& o : input.soil) fields.push_back(soil::findSoilField(o.key));
    auto value = [](std::span<const double> values, std::size_t i) {
        return values.size() == 1 ? values[0] : values[i];
    };
    const std::size_t n = input.count;
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> done{0};
    std::mutex progress_mutex;
    auto work = [&] {
        for (;;) {
            if (control.cancel && control.cancel->load(std::memory_order_relaxed)) return;
            const std::size_t i = next.fetch_add(1);
            if (i >= n) return;
            if (status[i] == SampleStatus::kOk) {
                soil::SoilParameters soil = study_.soil;
                for (std::size_t k = 0; k < fields.size(); ++k)
                    soil::setUserValue(soil, *fields[k], value(input.soil[k].values, i));
                compaction::PassConditions conditions;
                conditions.load_n = value(input.load_n, i);
                conditions.slip = value(input.slip, i);
                conditions.slip_angle_rad =
                    input.slip_angle_rad.empty() ? 0.0 : value(input.slip_angle_rad, i);
                conditions.exit = study_.model.exit;
                conditions.max_stress_angle_rad = study_.model.max_stress_angle_rad;
                conditions.bulldozing = study_.model.bulldozing;
                conditions.model = study_.model.model;
                const CompactionValues v =
                    evaluateCompaction(contact::makeContactParameters(soil, study_.wheel),
                                       conditions, c, layers, stresses, red);
                if (!v.ok) {
                    status[i] = SampleStatus::kNoEquilibrium;
                } else {
                    for (std::size_t o : slots) {
                        const Output which = study_.outputs[o];
                        buffers[o][i] = which == Output::kMaxSigmaZ  ? v.max_sigma_z_kpa
                                        : which == Output::kRedDepth ? v.red_depth_m
                                                                     : v.rut_m;
                    }
                }
            }
            const std::size_t finished = done.fetch_add(1) + 1;
            if (control.progress && finished % std::max<std::size_t>(1, n / 100) == 0) {
                std::lock_guard lock(progress_mutex);
                control.progress(static_cast<double>(finished) / n);
            }
        }
    };
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t threads = std::max<std::size_t>(
        1, std::min<std::size_t>(n, control.threads > 0 ? control.threads : hardware));
    {
        std::vector<std::jthread> pool;
        for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
        work();
    }
    // Samples a cancel left unevaluated.
    for (std::size_t i = next.load(); i < n; ++i)
        if (status[i] == SampleStatus::kOk) status[i] = SampleStatus::kNotEvaluated;
}

TargetValues evaluateInChunks(
    const WheelTarget& target, std::size_t rows, std::size_t chunk_rows, std::size_t row_multiple,
    const std::function<Eigen::MatrixXd(std::size_t, std::size_t)>& rows_of,
    const RunControl& control) {
    const std::size_t multiple = std::max<std::size_t>(1, row_multiple);
    const std::size_t chunk = std::max(multiple, chunk_rows / multiple * multiple);
    std::vector<TargetValues> chunks;
    for (std::size_t begin = 0; begin < rows; begin += chunk) {
        const std::size_t end = std::min(rows, begin + chunk);
        if (control.cancel && control.cancel->load()) {
            TargetValues skipped;
            skipped.values = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows - begin),
                                                   static_cast<Eigen::Index>(target.columns()));
            skipped.status = StatusMatrix::Constant(
                static_cast<Eigen::Index>(rows - begin), static_cast<Eigen::Index>(target.points()),
                static_cast<std::uint8_t>(SampleStatus::kNotEvaluated));
            skipped.cancelled = true;
            chunks.push_back(std::move(skipped));
            break;
        }
        RunControl chunk_control = control;
        if (control.progress) {
            chunk_control.progress = [&, begin, end](double fraction) {
                control.progress((begin + fraction * (end - begin)) / rows);
            };
        }
        chunks.push_back(target.evaluate(rows_of(begin, end), chunk_control));
    }
    return concatenate(chunks);
}

Mask WheelTarget::successMask(const TargetValues& values) const {
    const Eigen::Index rows = values.status.rows();
    const auto points = static_cast<Eigen::Index>(this->points());
    Mask ok(rows, static_cast<Eigen::Index>(columns()));
    for (Eigen::Index o = 0; o < static_cast<Eigen::Index>(study_.outputs.size()); ++o) {
        ok.middleCols(o * points, points) =
            values.status.array() == static_cast<std::uint8_t>(SampleStatus::kOk);
    }
    return ok;
}

std::vector<FailureCounts> WheelTarget::failures(const TargetValues& values) const {
    std::vector<FailureCounts> out(points());
    for (Eigen::Index r = 0; r < values.status.rows(); ++r) {
        for (std::size_t p = 0; p < points(); ++p) {
            switch (static_cast<SampleStatus>(values.status(r, static_cast<Eigen::Index>(p)))) {
                case SampleStatus::kNoEquilibrium:
                    ++out[p].no_equilibrium;
                    break;
                case SampleStatus::kLoadNotMatched:
                    ++out[p].load_not_matched;
                    break;
                case SampleStatus::kInvalidSoil:
                    ++out[p].invalid_soil;
                    break;
                case SampleStatus::kNonFinite:
                    ++out[p].non_finite;
                    break;
                case SampleStatus::kOk:
                case SampleStatus::kNotEvaluated:
                    break;
            }
        }
    }
    return out;
}

}  // namespace terra::gsa
