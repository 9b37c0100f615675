#include "core/project/saved_identification.h"

#include <stdexcept>

#include "core/project/result_json.h"

namespace terra::project {
namespace {

using nlohmann::json;
using saved::arrayFrom;
using saved::arrayJson;
using saved::flagsFrom;
using saved::number;
using saved::numberAt;
using saved::optionalAt;
using saved::optionalJson;
using saved::readKey;
namespace id = identification;

constexpr std::size_t kParameters = id::kFullParameterCount;
constexpr std::size_t kChannels = id::kChannelCount;

/// An enum saved as its number, refused outside [0, last].
template <typename Enum>
Enum enumAt(const json& j, const char* key, Enum last) {
    const int v = j.at(key).get<int>();
    if (v < 0 || v > static_cast<int>(last))
        throw std::invalid_argument(std::string(key) + ": " + std::to_string(v) +
                                    " is not a known value");
    return static_cast<Enum>(v);
}

json issuesJson(const std::vector<Issue>& issues) {
    json out = json::array();
    for (const Issue& i : issues) out.push_back({i.where, i.message});
    return out;
}

std::vector<Issue> issuesFrom(const json& j) {
    std::vector<Issue> out;
    for (const json& i : j) out.push_back({i.at(0).get<std::string>(), i.at(1).get<std::string>()});
    return out;
}

json sampleJson(const id::Sample& s) {
    return {{"slip", number(s.slip)},
            {"entry_angle_rad", number(s.entry_angle_rad)},
            {"fx_n", number(s.fx_n)},
            {"fz_n", number(s.fz_n)},
            {"my_nm", number(s.my_nm)},
            {"slip_angle_rad", optionalJson(s.slip_angle_rad)},
            {"fy_n", optionalJson(s.fy_n)},
            {"load_n", optionalJson(s.load_n)},
            {"time_s", optionalJson(s.time_s)},
            {"sinkage_m", optionalJson(s.sinkage_m)},
            {"slip_std", optionalJson(s.slip_std)}};
}

id::Sample sampleFrom(const json& j) {
    id::Sample s;
    s.slip = numberAt(j, "slip");
    s.entry_angle_rad = numberAt(j, "entry_angle_rad");
    s.fx_n = numberAt(j, "fx_n");
    s.fz_n = numberAt(j, "fz_n");
    s.my_nm = numberAt(j, "my_nm");
    s.slip_angle_rad = optionalAt(j, "slip_angle_rad");
    s.fy_n = optionalAt(j, "fy_n");
    s.load_n = optionalAt(j, "load_n");
    s.time_s = optionalAt(j, "time_s");
    s.sinkage_m = optionalAt(j, "sinkage_m");
    s.slip_std = optionalAt(j, "slip_std");  // absent in files written before it
    return s;
}

json dataJson(const id::DataSet& d) {
    json samples = json::array();
    for (const id::Sample& s : d.samples) samples.push_back(sampleJson(s));
    return {{"samples", std::move(samples)},
            {"columns", {d.columns.entry_angle, d.columns.fx, d.columns.fz, d.columns.my}}};
}

id::DataSet dataFrom(const json& j) {
    id::DataSet d;
    for (const json& s : j.at("samples")) d.samples.push_back(sampleFrom(s));
    const std::array<bool, 4> c = flagsFrom<4>(j.at("columns"));
    d.columns = {c[0], c[1], c[2], c[3]};
    return d;
}

json parametersJson(const id::DecoupledParameters& p) {
    return {number(p.a0),
            number(p.a1),
            number(p.pressure_modulus),
            number(p.n0),
            number(p.n1),
            number(p.cohesion_pa),
            number(p.friction_angle_rad),
            number(p.shear_modulus_m),
            number(p.max_shear_deformation_m)};
}

id::DecoupledParameters parametersFrom(const json& j) {
    const std::array<double, 9> v = arrayFrom<9>(j);
    return {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]};
}

json stepJson(const id::StepReport& s) {
    return {{"name", s.name.text},
            {"usable", s.usable},
            {"termination", s.termination},
            {"iterations", s.iterations},
            {"squared_residual_norm", number(s.squared_residual_norm)},
            {"wall_time_ms", number(s.wall_time_ms)}};
}

id::StepReport stepFrom(const json& j) {
    return {id::ParameterText(j.at("name").get<std::string>()),
            j.at("usable").get<bool>(),
            j.at("termination").get<std::string>(),
            j.at("iterations").get<int>(),
            numberAt(j, "squared_residual_norm"),
            numberAt(j, "wall_time_ms")};
}

json minimumJson(const id::Minimum& m) {
    return {{"parameters", arrayJson(m.parameters)},
            {"std", arrayJson(m.std)},
            {"chi2", number(m.chi2)},
            {"delta_chi2", number(m.delta_chi2)},
            {"label", m.label}};
}

id::Minimum minimumFrom(const json& j) {
    return {arrayFrom<kParameters>(j.at("parameters")), arrayFrom<kParameters>(j.at("std")),
            numberAt(j, "chi2"), numberAt(j, "delta_chi2"), j.at("label").get<std::string>()};
}

template <typename T, typename F>
json listJson(const std::vector<T>& items, F f) {
    json out = json::array();
    for (const T& item : items) out.push_back(f(item));
    return out;
}

template <typename T, typename F>
std::vector<T> listFrom(const json& j, F f) {
    if (!j.is_array()) throw std::invalid_argument("expected a list");
    std::vector<T> out;
    out.reserve(j.size());
    for (const json& item : j) out.push_back(f(item));
    return out;
}

json uncertaintyJson(const id::Uncertainty& u) {
    json correlation = json::array();
    for (const auto& row : u.correlation) correlation.push_back(arrayJson(row));
    return {{"computed", u.computed},
            {"std", arrayJson(u.std)},
            {"correlation", std::move(correlation)},
            {"flags", listJson(u.flags, [](const id::ParameterText& t) { return t.text; })}};
}

id::Uncertainty uncertaintyFrom(const json& j) {
    id::Uncertainty u;
    u.computed = j.at("computed").get<bool>();
    u.std = arrayFrom<kParameters>(j.at("std"));
    const json& correlation = j.at("correlation");
    if (!correlation.is_array() || correlation.size() != kParameters)
        throw std::invalid_argument("correlation: expected " + std::to_string(kParameters) +
                                    " rows");
    for (std::size_t i = 0; i < kParameters; ++i)
        u.correlation[i] = arrayFrom<kParameters>(correlation[i]);
    // The texts with their parameter references (parameter_text.h); a result saved before they
    // named parameters so reads as the text it was.
    for (std::string& flag : j.at("flags").get<std::vector<std::string>>())
        u.flags.emplace_back(std::move(flag));
    return u;
}

json setupJson(const id::ModelSetup& s) {
    return {{"source", static_cast<int>(s.source)},
            {"channels", s.channels},
            {"loads_n", listJson(s.loads_n, [](double v) { return number(v); })},
            {"max_shear_deformation_m", number(s.max_shear_deformation_m)},
            {"max_shear_deformation_free", s.max_shear_deformation_free},
            {"sinkage_exponent_slip", number(s.sinkage_exponent_slip)},
            {"slip_sinkage_coefficient", number(s.slip_sinkage_coefficient)},
            {"description", s.description}};
}

id::ModelSetup setupFrom(const json& j) {
    id::ModelSetup s;
    s.source = enumAt(j, "source", id::DataSource::kLoad);
    s.channels = flagsFrom<kChannels>(j.at("channels"));
    s.loads_n = listFrom<double>(j.at("loads_n"), [](const json& v) { return saved::numberOf(v); });
    s.max_shear_deformation_m = numberAt(j, "max_shear_deformation_m");
    s.max_shear_deformation_free = j.at("max_shear_deformation_free").get<bool>();
    s.sinkage_exponent_slip = numberAt(j, "sinkage_exponent_slip");
    s.slip_sinkage_coefficient = numberAt(j, "slip_sinkage_coefficient");
    s.description = j.at("description").get<std::string>();
    return s;
}

json trendJson(const id::TrendTest& t) {
    return {t.values, t.sweeps, t.trend_dof, number(t.f), number(t.trend_share), number(t.p)};
}

id::TrendTest trendFrom(const json& j) {
    id::TrendTest t;
    t.values = j.at(0).get<int>();
    t.sweeps = j.at(1).get<int>();
    t.trend_dof = j.at(2).get<int>();
    t.f = saved::numberOf(j.at(3));
    t.trend_share = saved::numberOf(j.at(4));
    t.p = saved::numberOf(j.at(5));
    return t;
}

json priorJson(const id::PriorComparison& p) {
    return {p.active,
            number(p.prior_mean),
            number(p.prior_std),
            number(p.posterior_mean),
            number(p.posterior_std),
            number(p.shift_in_prior_std),
            number(p.std_ratio)};
}

id::PriorComparison priorFrom(const json& j) {
    if (!j.is_array() || j.size() != 7) throw std::invalid_argument("prior: 7 values expected");
    return {j[0].get<bool>(),      saved::numberOf(j[1]), saved::numberOf(j[2]),
            saved::numberOf(j[3]), saved::numberOf(j[4]), saved::numberOf(j[5]),
            saved::numberOf(j[6])};
}

json startJson(const id::StartReport& s) {
    return {{"label", s.label},
            {"start", arrayJson(s.start)},
            {"screening_cost", number(s.screening_cost)},
            {"descended", s.descended},
            {"refined", s.refined},
            {"end", arrayJson(s.end)},
            {"chi2", number(s.chi2)},
            {"iterations", s.iterations},
            {"termination", s.termination}};
}

id::StartReport startFrom(const json& j) {
    id::StartReport s;
    s.label = j.at("label").get<std::string>();
    s.start = arrayFrom<kParameters>(j.at("start"));
    s.screening_cost = numberAt(j, "screening_cost");
    s.descended = j.at("descended").get<bool>();
    s.refined = j.at("refined").get<bool>();
    s.end = arrayFrom<kParameters>(j.at("end"));
    s.chi2 = numberAt(j, "chi2");
    s.iterations = j.at("iterations").get<int>();
    s.termination = j.at("termination").get<std::string>();
    return s;
}

json reportJson(const id::IdentificationReport& r) {
    json trend = json::array();
    for (const id::TrendTest& t : r.adequacy.trend) trend.push_back(trendJson(t));
    json prior = json::array();
    for (const id::PriorComparison& p : r.prior) prior.push_back(priorJson(p));
    const id::HoldoutReport& h = r.holdout;
    const id::IdentifyTiming& t = r.timing;
    return {
        {"status", static_cast<int>(r.status)},
        {"message", r.message},
        {"issues", issuesJson(r.issues)},
        {"setup", setupJson(r.setup)},
        {"parameters", arrayJson(r.parameters)},
        {"uncertainty", uncertaintyJson(r.uncertainty)},
        {"at_bound", r.at_bound},
        {"chi2", number(r.chi2)},
        {"residuals", r.residuals},
        {"free_parameters", r.free_parameters},
        {"noise", arrayJson(r.noise)},
        {"noise_estimated", r.noise_estimated},
        {"channel_values", r.channel_values},
        {"interpolated", r.interpolated},
        {"rms", arrayJson(r.rms)},
        {"adequacy",
         {{"trend", std::move(trend)}, {"p", number(r.adequacy.p)}, {"flag", r.adequacy.flag}}},
        {"gradient_norm", number(r.gradient_norm)},
        {"newton_decrement", number(r.newton_decrement)},
        {"iterations", r.iterations},
        {"termination", r.termination},
        {"starts", listJson(r.starts, startJson)},
        {"ambiguity", listJson(r.ambiguity, minimumJson)},
        {"ambiguity_delta_chi2", number(r.ambiguity_delta_chi2)},
        {"minima", listJson(r.minima, minimumJson)},
        {"prior", std::move(prior)},
        {"shear_limit_prior", r.shear_limit_prior},
        {"holdout",
         {{"computed", h.computed},
          {"folds", h.folds},
          {"samples", h.samples},
          {"failed", h.failed},
          {"channels", h.channels},
          {"rms", arrayJson(h.rms)},
          {"rms_in_fit", arrayJson(h.rms_in_fit)},
          {"rms_over_noise", arrayJson(h.rms_over_noise)}}},
        {"timing",
         {number(t.screening_ms), number(t.descent_ms), number(t.refinement_ms),
          number(t.covariance_ms), number(t.holdout_ms), number(t.total_ms)}},
    };
}

id::IdentificationReport reportFrom(const json& j) {
    id::IdentificationReport r;
    r.status = enumAt(j, "status", id::IdentifyStatus::kFailed);
    r.message = j.at("message").get<std::string>();
    r.issues = issuesFrom(j.at("issues"));
    r.setup = setupFrom(j.at("setup"));
    r.parameters = arrayFrom<kParameters>(j.at("parameters"));
    r.uncertainty = uncertaintyFrom(j.at("uncertainty"));
    r.at_bound = flagsFrom<kParameters>(j.at("at_bound"));
    r.chi2 = numberAt(j, "chi2");
    r.residuals = j.at("residuals").get<int>();
    r.free_parameters = j.at("free_parameters").get<int>();
    r.noise = arrayFrom<kChannels>(j.at("noise"));
    r.noise_estimated = j.at("noise_estimated").get<bool>();
    r.channel_values = j.at("channel_values").get<std::array<int, kChannels>>();
    r.interpolated = flagsFrom<kChannels>(j.at("interpolated"));
    r.rms = arrayFrom<kChannels>(j.at("rms"));
    const json& adequacy = j.at("adequacy");
    const json& trend = adequacy.at("trend");
    if (!trend.is_array() || trend.size() != kChannels)
        throw std::invalid_argument("adequacy.trend: expected one test per channel");
    for (std::size_t c = 0; c < kChannels; ++c) r.adequacy.trend[c] = trendFrom(trend[c]);
    r.adequacy.p = numberAt(adequacy, "p");
    r.adequacy.flag = adequacy.at("flag").get<bool>();
    r.gradient_norm = numberAt(j, "gradient_norm");
    r.newton_decrement = numberAt(j, "newton_decrement");
    r.iterations = j.at("iterations").get<int>();
    r.termination = j.at("termination").get<std::string>();
    r.starts = listFrom<id::StartReport>(j.at("starts"), startFrom);
    r.ambiguity = listFrom<id::Minimum>(j.at("ambiguity"), minimumFrom);
    r.ambiguity_delta_chi2 = numberAt(j, "ambiguity_delta_chi2");
    r.minima = listFrom<id::Minimum>(j.at("minima"), minimumFrom);
    const json& prior = j.at("prior");
    if (!prior.is_array() || prior.size() != kParameters)
        throw std::invalid_argument("prior: expected one comparison per parameter");
    for (std::size_t i = 0; i < kParameters; ++i) r.prior[i] = priorFrom(prior[i]);
    r.shear_limit_prior = j.at("shear_limit_prior").get<bool>();
    const json& h = j.at("holdout");
    r.holdout.computed = h.at("computed").get<bool>();
    r.holdout.folds = h.at("folds").get<int>();
    r.holdout.samples = h.at("samples").get<std::size_t>();
    r.holdout.failed = h.at("failed").get<std::size_t>();
    r.holdout.channels = flagsFrom<kChannels>(h.at("channels"));
    r.holdout.rms = arrayFrom<kChannels>(h.at("rms"));
    r.holdout.rms_in_fit = arrayFrom<kChannels>(h.at("rms_in_fit"));
    r.holdout.rms_over_noise = arrayFrom<kChannels>(h.at("rms_over_noise"));
    const std::array<double, 6> t = arrayFrom<6>(j.at("timing"));
    r.timing = {t[0], t[1], t[2], t[3], t[4], t[5]};
    return r;
}

json profileJson(const id::ProfileInterval& p) {
    return {p.computed,       number(p.lower),      number(p.upper), p.lower_at_bound,
            p.upper_at_bound, number(p.delta_chi2), p.fits};
}

id::ProfileInterval profileFrom(const json& j) {
    if (!j.is_array() || j.size() != 7) throw std::invalid_argument("profile: 7 values expected");
    id::ProfileInterval p;
    p.computed = j[0].get<bool>();
    p.lower = saved::numberOf(j[1]);
    p.upper = saved::numberOf(j[2]);
    p.lower_at_bound = j[3].get<bool>();
    p.upper_at_bound = j[4].get<bool>();
    p.delta_chi2 = saved::numberOf(j[5]);
    p.fits = j[6].get<int>();
    return p;
}

json estimateJson(const id::StreamEstimate& e) {
    return {{"index", e.index},
            {"estimated", e.estimated},
            {"initialised", e.initialised},
            {"refitted", e.refitted},
            {"parameters", arrayJson(e.parameters)},
            {"std", arrayJson(e.std)},
            {"nis", number(e.nis)},
            {"channels", e.channels},
            {"used", e.used},
            {"cusum", number(e.cusum)},
            {"change_detected", e.change_detected},
            {"change_rejected", e.change_rejected},
            {"change_statistic", number(e.change_statistic)},
            {"change_at", e.change_at ? json(*e.change_at) : json(nullptr)},
            {"update_ms", number(e.update_ms)}};
}

id::StreamEstimate estimateFrom(const json& j) {
    id::StreamEstimate e;
    e.index = j.at("index").get<std::size_t>();
    e.estimated = j.at("estimated").get<bool>();
    e.initialised = j.at("initialised").get<bool>();
    e.refitted = j.at("refitted").get<bool>();
    e.parameters = arrayFrom<kParameters>(j.at("parameters"));
    e.std = arrayFrom<kParameters>(j.at("std"));
    e.nis = numberAt(j, "nis");
    e.channels = j.at("channels").get<int>();
    e.used = j.at("used").get<bool>();
    e.cusum = numberAt(j, "cusum");
    e.change_detected = j.at("change_detected").get<bool>();
    e.change_rejected = j.at("change_rejected").get<bool>();
    e.change_statistic = numberAt(j, "change_statistic");
    if (!j.at("change_at").is_null()) e.change_at = j.at("change_at").get<std::size_t>();
    e.update_ms = numberAt(j, "update_ms");
    return e;
}

}  // namespace

json savedJson(const id::IdentificationReport& report) { return reportJson(report); }

id::IdentificationReport identificationReportFromJson(const json& j) { return reportFrom(j); }

json savedJson(const analysis::IdentificationResult& r) {
    json profile = json::array();
    for (const id::ProfileInterval& p : r.profile) profile.push_back(profileJson(p));
    return {{"data", dataJson(r.data)},
            {"skipped", issuesJson(r.skipped)},
            {"warnings", r.warnings},
            {"fit",
             {{"parameters", parametersJson(r.fit.parameters)},
              {"steps", listJson(r.fit.steps, stepJson)}}},
            {"report", r.report ? reportJson(*r.report) : json(nullptr)},
            {"identified", parametersJson(r.identified)},
            {"curves", saved::tableJson(r.curves)},
            {"parameters", saved::tableJson(r.parameters)},
            {"fit_time_ms", number(r.fit_time_ms)},
            {"profile", std::move(profile)},
            {"profile_time_ms", number(r.profile_time_ms)},
            {"message", r.message},
            {"data_issues", issuesJson(r.data_issues)},
            {"start_description", r.start_description}};
}

Result<analysis::IdentificationResult> identificationResultFromJson(const json& j,
                                                                    const std::string& where) {
    try {
        analysis::IdentificationResult r;
        r.data = readKey(j, "data", dataFrom);
        r.skipped = readKey(j, "skipped", issuesFrom);
        r.warnings = j.at("warnings").get<std::vector<std::string>>();
        const json& fit = j.at("fit");
        r.fit.parameters = readKey(fit, "parameters", parametersFrom);
        r.fit.steps = readKey(fit, "steps", [](const json& steps) {
            return listFrom<id::StepReport>(steps, stepFrom);
        });
        if (!j.at("report").is_null()) r.report = readKey(j, "report", reportFrom);
        r.identified = readKey(j, "identified", parametersFrom);
        r.curves = readKey(j, "curves", saved::tableFrom);
        r.parameters = readKey(j, "parameters", saved::tableFrom);
        r.fit_time_ms = numberAt(j, "fit_time_ms");
        const json& profile = j.at("profile");
        if (!profile.is_array() || profile.size() != kParameters)
            throw std::invalid_argument("profile: expected one interval per parameter");
        for (std::size_t i = 0; i < kParameters; ++i) r.profile[i] = profileFrom(profile[i]);
        r.profile_time_ms = numberAt(j, "profile_time_ms");
        r.message = j.at("message").get<std::string>();
        r.data_issues = readKey(j, "data_issues", issuesFrom);
        // A saved result with a message had nothing to fit (a cancelled fit is never saved).
        if (!r.message.empty()) r.status = analysis::Outcome::Status::kInvalidInput;
        r.start_description = j.at("start_description").get<std::string>();
        // The curves are drawn per sample and the parameter table has one row: anything else
        // is not a fit this studio wrote.
        if (r.message.empty() &&
            (r.curves.rows.size() != r.data.samples.size() || r.parameters.rows.size() != 1))
            return std::vector<Issue>{
                {where, "the curves or parameters do not match the data (" +
                            std::to_string(r.curves.rows.size()) + " curve rows for " +
                            std::to_string(r.data.samples.size()) + " samples)"}};
        return r;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

json savedJson(const SavedStream& s) {
    json frames = json::array();
    for (const analysis::StreamFrame& f : s.frames) {
        frames.push_back({{"estimate", estimateJson(f.estimate)},
                          {"parameters", parametersJson(f.parameters)},
                          {"time_s", number(f.time_s)},
                          {"fx_measured_n", number(f.fx_measured_n)},
                          {"fx_predicted_n", number(f.fx_predicted_n)}});
    }
    json truth = json::array();
    for (const auto& [from, p] : s.truth) truth.push_back({from, parametersJson(p)});
    return {{"frames", std::move(frames)},
            {"sample_count", s.sample_count},
            {"true_border", s.true_border ? json(*s.true_border) : json(nullptr)},
            {"description", s.description},
            {"warnings", s.warnings},
            {"truth", std::move(truth)},
            {"stopped", s.stopped}};
}

Result<SavedStream> savedStreamFromJson(const json& j, const std::string& where) {
    try {
        SavedStream s;
        const json& frames = j.at("frames");
        if (!frames.is_array()) throw std::invalid_argument("frames: expected a list");
        s.frames.reserve(frames.size());
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const json& f = frames[i];
            try {
                analysis::StreamFrame frame;
                frame.estimate = readKey(f, "estimate", estimateFrom);
                frame.parameters = readKey(f, "parameters", parametersFrom);
                frame.time_s = numberAt(f, "time_s");
                frame.fx_measured_n = numberAt(f, "fx_measured_n");
                frame.fx_predicted_n = numberAt(f, "fx_predicted_n");
                s.frames.push_back(frame);
            } catch (const std::exception& e) {
                throw std::invalid_argument("frames[" + std::to_string(i) + "]: " + e.what());
            }
        }
        s.sample_count = j.at("sample_count").get<std::size_t>();
        if (!j.at("true_border").is_null()) s.true_border = j.at("true_border").get<std::size_t>();
        s.description = j.at("description").get<std::string>();
        s.warnings = j.at("warnings").get<std::vector<std::string>>();
        for (const json& t : j.at("truth"))
            s.truth.emplace_back(t.at(0).get<std::size_t>(), parametersFrom(t.at(1)));
        s.stopped = j.at("stopped").get<bool>();
        if (s.frames.size() > s.sample_count)
            return std::vector<Issue>{{where, std::to_string(s.frames.size()) + " frames for " +
                                                  std::to_string(s.sample_count) + " samples"}};
        return s;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace terra::project
