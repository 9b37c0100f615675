#include "core/analysis/streaming_identification.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/analysis/identified_parameters.h"
#include "core/analysis/registry.h"
#include "core/contact/contact_parameters.h"
#include "core/identification/synthetic.h"
#include "core/io/declared_json.h"
#include "core/io/parameters_json.h"

namespace terra::analysis {
namespace {

namespace id = identification;

constexpr double kDefaultPeriodS = 0.01;  // 100 Hz when the data carry no time

// One soil's sweep in a scrambled, fixed order (stride coprime to the count).
std::vector<id::Sample> scrambledSweep(const soil::SoilParameters& soil, const SoilBorderSpec& spec,
                                       std::uint64_t seed, std::vector<std::string>& warnings) {
    id::SyntheticSpec s;
    s.loads_n = {spec.load_n};
    const int n = spec.samples_per_soil;
    for (int i = 0; i < n; ++i) s.slips.push_back(n == 1 ? 0.3 : 0.05 + 0.85 * i / (n - 1));
    s.noise.fx.relative = s.noise.fz.relative = s.noise.my.relative = spec.noise_relative;
    s.seed = seed;
    id::SyntheticData d = id::synthesize(contact::makeContactParameters(soil, spec.wheel), s);
    for (auto& w : d.warnings) warnings.push_back(soil.name + ": " + w);
    const std::size_t count = d.data.samples.size();
    std::size_t stride = 37;
    while (count > 1 && std::gcd(stride, count) != 1) ++stride;
    std::vector<id::Sample> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) out.push_back(d.data.samples[(i * stride) % count]);
    return out;
}

}  // namespace

StreamSource synthesiseSoilBorder(const SoilBorderSpec& spec) {
    if (spec.samples_per_soil < 1) {
        throw std::invalid_argument("samples_per_soil = " + std::to_string(spec.samples_per_soil) +
                                    " must be ≥ 1");
    }
    if (!(spec.sample_period_s > 0.0)) throw std::invalid_argument("sample_period_s must be > 0");
    StreamSource out;
    std::vector<id::Sample> samples = scrambledSweep(spec.first, spec, spec.seed, out.warnings);
    out.true_border = samples.size();
    const std::vector<id::Sample> second =
        scrambledSweep(spec.second, spec, spec.seed + 1, out.warnings);
    samples.insert(samples.end(), second.begin(), second.end());
    for (std::size_t i = 0; i < samples.size(); ++i)
        samples[i].time_s = static_cast<double>(i) * spec.sample_period_s;
    out.data.samples = std::move(samples);
    out.truth = {{0, identification::decoupledOf(spec.first, spec.wheel)},
                 {*out.true_border, identification::decoupledOf(spec.second, spec.wheel)}};
    const auto percent = static_cast<int>(std::lround(spec.noise_relative * 100.0));
    out.description =
        spec.first.name + " → " + spec.second.name + ", " + std::to_string(percent) + " % noise";
    return out;
}

Result<StreamSource> readStreamSource(const std::string& path, bool skip_bad_rows) {
    auto read = id::readDataSet(path, skip_bad_rows ? id::BadRows::kSkip : id::BadRows::kStop,
                                id::ColumnNeeds::kFullModel);
    if (!read) return read.issues();
    StreamSource out;
    out.data = read->data;
    out.description = std::filesystem::path(path).filename().string();
    for (const Issue& issue : read->warnings)
        out.warnings.push_back("warning: " + issue.where + ": " + issue.message);
    for (const Issue& issue : read->skipped)
        out.warnings.push_back("skipped " + issue.where + ": " + issue.message);
    if (out.data.samples.empty()) return std::vector<Issue>{{path, "no valid samples"}};
    return out;
}

void readStreamingSettings(io::ObjectReader& r, const ReadContext& context,
                           StreamingSettings& out) {
    io::readFields(r, out, context.base_dir);
    if (r.has("csv") && !out.csv.empty()) {
        if (Result<StreamSource> read = readStreamSource(out.csv, out.skip_bad_rows); !read) {
            for (const Issue& issue : read.issues())
                r.report("csv", issue.where + ": " + issue.message);
        }
    }
    const nlohmann::json* second = r.value("second_soil");
    if (((second != nullptr && second->is_string()) || out.csv.empty()) &&
        context.locations != nullptr) {
        Result<soil::SoilParameters> soil =
            io::resolveSoil(*context.locations, context.presetOrFile(out.second_soil));
        if (soil) {
            out.second = soil.value();
        } else {
            r.report("second_soil", soil.message());
        }
    }
}

nlohmann::json toJson(const StreamingSettings& settings) { return io::fieldsToJson(settings); }

void readStreamingWindow(io::ObjectReader& r, const char* key, std::size_t& out) {
    int window = static_cast<int>(out);
    if (r.integer(key, window, 1, kMaxStreamingWindow)) out = static_cast<std::size_t>(window);
}

StreamSource streamSource(const Inputs& in, const StreamingSettings& s) {
    // The reader's checks, in its words, for settings built in code (a panel's, a test's).
    if (const std::vector<Issue> issues = io::fieldIssues(s); !issues.empty())
        throw std::invalid_argument(formatIssues(issues));
    if (!s.csv.empty()) {
        Result<StreamSource> read = readStreamSource(s.csv, s.skip_bad_rows);
        if (!read) throw std::invalid_argument(read.message());
        return read.value();
    }
    if (!s.second)
        throw std::invalid_argument("second_soil: the soil after the border is not resolved");
    SoilBorderSpec spec;
    spec.first = in.soil;
    spec.second = *s.second;
    spec.wheel = in.wheel;
    spec.load_n = in.conditions.load_n;
    spec.noise_relative = s.noise_percent / 100.0;
    spec.seed = s.seed;
    return synthesiseSoilBorder(spec);
}

std::vector<double> sampleTimes(const id::DataSet& data) {
    std::vector<double> t(data.samples.size());
    bool own = !data.samples.empty();
    for (std::size_t i = 0; i < t.size() && own; ++i) {
        own = data.samples[i].time_s.has_value() && std::isfinite(*data.samples[i].time_s) &&
              (i == 0 || *data.samples[i].time_s >= *data.samples[i - 1].time_s);
        if (own) t[i] = *data.samples[i].time_s;
    }
    if (!own) {
        for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<double>(i) * kDefaultPeriodS;
    }
    return t;
}

StreamingRun::StreamingRun(const wheel::WheelParameters& wheel,
                           const id::StreamingEstimatorOptions& options)
    : wheel_(wheel), options_(options), estimator_(wheel, options) {}

StreamFrame StreamingRun::push(const id::Sample& sample, double time_s) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    StreamFrame frame;
    frame.time_s = time_s;
    frame.fx_measured_n = options_.columns.fx ? sample.fx_n : nan;
    frame.fx_predicted_n = nan;
    if (estimate_ && options_.columns.fx) {
        // The prediction of the estimate before the sample, on the estimator's own model.
        try {
            const std::vector<id::Prediction> p = id::predictAll(
                id::DataSet({sample}, options_.columns), wheel_, *estimate_, options_.fit);
            if (!p.empty() && p.front().ok) frame.fx_predicted_n = p.front().values[id::kFxChannel];
        } catch (const std::invalid_argument&) {
            // a sample the model cannot read (no load): no prediction
        }
    }
    frame.estimate = estimator_.push(sample);
    if (frame.estimate.estimated) {
        estimate_ = frame.estimate.parameters;
        const double jmax = frame.parameters.max_shear_deformation_m;
        frame.parameters = id::decoupledOf(frame.estimate.parameters);
        // j_max as the frame has always shown it (its default, none): the table unchanged.
        frame.parameters.max_shear_deformation_m = jmax;
    } else {
        estimate_.reset();
    }
    return frame;
}

Table framesTable(const std::vector<StreamFrame>& frames) {
    Table t;
    t.columns = {"sample", "time_s", "estimated"};
    // The streaming estimator holds j_max at its options' value: no column of it.
    const auto streamed = [](const IdentifiedField& field) {
        return fullParameterOf(field) != id::kJmax;
    };
    for (const IdentifiedField& field : identifiedFields())
        if (streamed(field)) t.columns.emplace_back(field.key);
    for (int k = 0; k < id::kJmax; ++k)
        t.columns.push_back(std::string(fieldOf(static_cast<id::FullParameter>(k)).key) + "_std");
    for (const char* c : {"nis", "cusum", "used", "change_at", "Fx_N", "Fx_predicted_N"})
        t.columns.emplace_back(c);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const StreamFrame& f : frames) {
        const id::StreamEstimate& u = f.estimate;
        std::vector<double> row{static_cast<double>(u.index), f.time_s, u.estimated ? 1.0 : 0.0};
        for (const IdentifiedField& field : identifiedFields()) {
            if (streamed(field))
                row.push_back(u.estimated ? field.toUser(f.parameters.*field.member) : nan);
        }
        for (int k = 0; k < id::kJmax; ++k) {
            const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
            row.push_back(u.estimated ? u.std[static_cast<std::size_t>(k)] / field.to_si : nan);
        }
        row.insert(row.end(), {u.nis, u.cusum, u.used ? 1.0 : 0.0,
                               u.change_at ? static_cast<double>(*u.change_at) : nan,
                               f.fx_measured_n, f.fx_predicted_n});
        t.rows.push_back(std::move(row));
    }
    return t;
}

StreamingResult computeStreaming(const Inputs& in, const StreamingSettings& s,
                                 const Control& control) {
    return playStreaming(streamSource(in, s), in.wheel, streamingOptions(in, s), control);
}

id::StreamingEstimatorOptions streamingOptions(const Inputs& in, const StreamingSettings& s) {
    id::StreamingEstimatorOptions options = s.options;
    // Synthetic data are made from the inputs' soil: its j_max is their model's. A CSV's model
    // never depends on the inputs' soil (the settings' j_max, none by default).
    if (s.csv.empty() && !std::isfinite(options.fit.max_shear_deformation_m))
        options.fit.max_shear_deformation_m = in.soil.max_shear_deformation_m;
    return options;
}

StreamingResult playStreaming(StreamSource source, const wheel::WheelParameters& wheel,
                              id::StreamingEstimatorOptions options, const Control& control) {
    StreamingResult out;
    out.source = std::move(source);
    const std::vector<id::Sample> samples = std::move(out.source.data.samples);
    out.source.data.samples.clear();
    if (samples.empty()) throw std::invalid_argument("the data set has no samples");
    out.sample_count = samples.size();
    const std::vector<double> times = sampleTimes(id::DataSet{samples});
    options.columns = out.source.data.columns;
    StreamingRun run(wheel, options);
    out.frames.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (control.cancelled()) {
            out.cancelled = true;
            break;
        }
        out.frames.push_back(run.push(samples[i], times[i]));
        const id::StreamEstimate& u = out.frames.back().estimate;
        if (u.change_detected && u.change_at) out.changes.push_back(*u.change_at);
        control.report(static_cast<double>(i + 1) / static_cast<double>(samples.size()));
    }
    return out;
}

Outcome streamingOutcome(StreamingResult result) {
    Outcome out;
    out.status = result.cancelled ? Outcome::Status::kCancelled : Outcome::Status::kCompleted;
    out.tables.push_back({"frames", "", framesTable(result.frames)});
    out.notes = result.source.warnings;
    std::string changes;
    for (std::size_t c : result.changes)
        changes += (changes.empty() ? "" : ", ") + std::to_string(c);
    out.notes.push_back(changes.empty() ? "no change of soil detected"
                                        : "change of soil at sample " + changes);
    if (result.source.true_border) {
        out.notes.push_back("true border at sample " + std::to_string(*result.source.true_border));
    }
    out.result = std::move(result);
    return out;
}

AnalysisType streamingType() {
    return makeAnalysisType<StreamingSettings>(
        "streaming",
        "streaming identification of a CSV or of a synthetic drive over a soil border, with the "
        "detected change of soil",
        {"frames"}, {{"estimates", "-estimates"}, {"detection", "-detection"}},
        readStreamingSettings,
        [](const Inputs& in, const StreamingSettings& s, const Control& c) {
            return computeStreaming(in, s, c);
        },
        streamingOutcome);
}

}  // namespace terra::analysis
