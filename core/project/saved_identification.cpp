#include "core/project/saved_identification.h"

#include <stdexcept>

#include "core/project/result_json.h"

namespace terra::project::saved {
namespace id = identification;

template <>
struct EnumLast<id::IdentifyStatus> {
    static constexpr id::IdentifyStatus value = id::IdentifyStatus::kFailed;
};
template <>
struct EnumLast<id::DataSource> {
    static constexpr id::DataSource value = id::DataSource::kLoad;
};
// The force model's only saved form (a second specialisation elsewhere would clash: keep it here).
template <>
struct EnumLast<contact::ContactModel> {
    static constexpr contact::ContactModel value = contact::ContactModel::kQuadratic;
};

/// A text that may name parameters ("{c_kPa} and {phi_deg} trade off"), saved as its text; a
/// result saved before texts named parameters reads as the text it was.
template <>
struct Value<id::ParameterText> {
    static nlohmann::json write(const id::ParameterText& t) { return t.text; }
    static void read(const nlohmann::json& json, id::ParameterText& t) {
        t = id::ParameterText(json.get<std::string>());
    }
};

template <>
struct Fields<id::Sample> {
    template <typename V>
    static void visit(V& v, id::Sample& s) {
        v("slip", s.slip);
        v("entry_angle_rad", s.entry_angle_rad);
        v("fx_n", s.fx_n);
        v("fz_n", s.fz_n);
        v("my_nm", s.my_nm);
        // Absent or null: not measured (the reader has always taken both).
        v("slip_angle_rad", s.slip_angle_rad, kSince);
        v("fy_n", s.fy_n, kSince);
        v("load_n", s.load_n, kSince);
        v("time_s", s.time_s, kSince);
        v("sinkage_m", s.sinkage_m, kSince);
        v("slip_std", s.slip_std, kSince);
    }
};

// Compact: [entry angle, F_x, F_z, M_y].
template <>
struct Compact<id::DataColumns> : std::true_type {};
template <>
struct Fields<id::DataColumns> {
    template <typename V>
    static void visit(V& v, id::DataColumns& c) {
        v("entry_angle", c.entry_angle);
        v("fx", c.fx);
        v("fz", c.fz);
        v("my", c.my);
    }
};

template <>
struct Fields<id::DataSet> {
    template <typename V>
    static void visit(V& v, id::DataSet& d) {
        v("samples", d.samples);
        v("columns", d.columns);
    }
};

// Compact: the nine values in the field table's order.
template <>
struct Compact<id::DecoupledParameters> : std::true_type {};
template <>
struct Fields<id::DecoupledParameters> {
    template <typename V>
    static void visit(V& v, id::DecoupledParameters& p) {
        v("a0", p.a0);
        v("a1", p.a1);
        v("pressure_modulus", p.pressure_modulus);
        v("n0", p.n0);
        v("n1", p.n1);
        v("cohesion_pa", p.cohesion_pa);
        v("friction_angle_rad", p.friction_angle_rad);
        v("shear_modulus_m", p.shear_modulus_m);
        v("max_shear_deformation_m", p.max_shear_deformation_m);
    }
};

template <>
struct Fields<id::StepReport> {
    template <typename V>
    static void visit(V& v, id::StepReport& s) {
        v("name", s.name);
        v("usable", s.usable);
        v("termination", s.termination);
        v("iterations", s.iterations);
        v("squared_residual_norm", s.squared_residual_norm);
        v("wall_time_ms", s.wall_time_ms);
    }
};

template <>
struct Fields<id::DecoupledFit> {
    template <typename V>
    static void visit(V& v, id::DecoupledFit& f) {
        v("parameters", f.parameters);
        v("steps", f.steps);
    }
};

template <>
struct Fields<id::Minimum> {
    template <typename V>
    static void visit(V& v, id::Minimum& m) {
        v("parameters", m.parameters);
        v("std", m.std);
        v("chi2", m.chi2);
        v("delta_chi2", m.delta_chi2);
        v("label", m.label);
    }
};

template <>
struct Fields<id::Uncertainty> {
    template <typename V>
    static void visit(V& v, id::Uncertainty& u) {
        v("computed", u.computed);
        v("std", u.std);
        v("correlation", u.correlation);
        v("flags", u.flags);
    }
};

template <>
struct Fields<id::ModelSetup> {
    template <typename V>
    static void visit(V& v, id::ModelSetup& s) {
        v("source", s.source);
        v("channels", s.channels);
        v("loads_n", s.loads_n);
        v("max_shear_deformation_m", s.max_shear_deformation_m);
        v("max_shear_deformation_free", s.max_shear_deformation_free);
        v("sinkage_exponent_slip", s.sinkage_exponent_slip);
        v("slip_sinkage_coefficient", s.slip_sinkage_coefficient);
        v("description", s.description);
        v("model", s.model, kSince);  // not saved before: such a file reads as the full model
    }
};

// Compact: [n, sweeps, k, F, trend share, p].
template <>
struct Compact<id::TrendTest> : std::true_type {};
template <>
struct Fields<id::TrendTest> {
    template <typename V>
    static void visit(V& v, id::TrendTest& t) {
        v("values", t.values);
        v("sweeps", t.sweeps);
        v("trend_dof", t.trend_dof);
        v("f", t.f);
        v("trend_share", t.trend_share);
        v("p", t.p);
    }
};

template <>
struct Fields<id::AdequacyReport> {
    template <typename V>
    static void visit(V& v, id::AdequacyReport& a) {
        v("trend", a.trend);
        v("p", a.p);
        v("flag", a.flag);
    }
};

// Compact: [active, prior mean, prior std, posterior mean, posterior std, shift, std ratio].
template <>
struct Compact<id::PriorComparison> : std::true_type {};
template <>
struct Fields<id::PriorComparison> {
    template <typename V>
    static void visit(V& v, id::PriorComparison& p) {
        v("active", p.active);
        v("prior_mean", p.prior_mean);
        v("prior_std", p.prior_std);
        v("posterior_mean", p.posterior_mean);
        v("posterior_std", p.posterior_std);
        v("shift_in_prior_std", p.shift_in_prior_std);
        v("std_ratio", p.std_ratio);
    }
};

template <>
struct Fields<id::StartReport> {
    template <typename V>
    static void visit(V& v, id::StartReport& s) {
        v("label", s.label);
        v("start", s.start);
        v("screening_cost", s.screening_cost);
        v("descended", s.descended);
        v("refined", s.refined);
        v("end", s.end);
        v("chi2", s.chi2);
        v("iterations", s.iterations);
        v("termination", s.termination);
    }
};

template <>
struct Fields<id::HoldoutReport> {
    template <typename V>
    static void visit(V& v, id::HoldoutReport& h) {
        v("computed", h.computed);
        v("folds", h.folds);
        v("samples", h.samples);
        v("failed", h.failed);
        v("channels", h.channels);
        v("rms", h.rms);
        v("rms_in_fit", h.rms_in_fit);
        v("rms_over_noise", h.rms_over_noise);
    }
};

// Compact: the phases' wall times [ms].
template <>
struct Compact<id::IdentifyTiming> : std::true_type {};
template <>
struct Fields<id::IdentifyTiming> {
    template <typename V>
    static void visit(V& v, id::IdentifyTiming& t) {
        v("screening_ms", t.screening_ms);
        v("descent_ms", t.descent_ms);
        v("refinement_ms", t.refinement_ms);
        v("covariance_ms", t.covariance_ms);
        v("holdout_ms", t.holdout_ms);
        v("total_ms", t.total_ms);
    }
};

template <>
struct Fields<id::IdentificationReport> {
    template <typename V>
    static void visit(V& v, id::IdentificationReport& r) {
        v("status", r.status);
        v("message", r.message);
        v("issues", r.issues);
        v("setup", r.setup);
        v("parameters", r.parameters);
        v("uncertainty", r.uncertainty);
        v("at_bound", r.at_bound);
        v("chi2", r.chi2);
        v("residuals", r.residuals);
        v("free_parameters", r.free_parameters);
        v("noise", r.noise);
        v("noise_estimated", r.noise_estimated);
        v("channel_values", r.channel_values);
        v("interpolated", r.interpolated);
        v("rms", r.rms);
        v("adequacy", r.adequacy);
        v("gradient_norm", r.gradient_norm);
        v("newton_decrement", r.newton_decrement);
        v("iterations", r.iterations);
        v("termination", r.termination);
        v("starts", r.starts);
        v("ambiguity", r.ambiguity);
        v("ambiguity_delta_chi2", r.ambiguity_delta_chi2);
        v("minima", r.minima);
        v("prior", r.prior);
        v("shear_limit_prior", r.shear_limit_prior);
        v("holdout", r.holdout);
        v("timing", r.timing);
    }
};

// Compact: [computed, lower, upper, lower at bound, upper at bound, Δχ², fits].
template <>
struct Compact<id::ProfileInterval> : std::true_type {};
template <>
struct Fields<id::ProfileInterval> {
    template <typename V>
    static void visit(V& v, id::ProfileInterval& p) {
        v("computed", p.computed);
        v("lower", p.lower);
        v("upper", p.upper);
        v("lower_at_bound", p.lower_at_bound);
        v("upper_at_bound", p.upper_at_bound);
        v("delta_chi2", p.delta_chi2);
        v("fits", p.fits);
    }
};

/// What was computed; the status and the checks against the data are the reader's (below).
template <>
struct Fields<analysis::IdentificationResult> {
    template <typename V>
    static void visit(V& v, analysis::IdentificationResult& r) {
        v("data", r.data);
        v("skipped", r.skipped);
        v("warnings", r.warnings);
        v("fit", r.fit);
        v("report", r.report);
        v("identified", r.identified);
        v("curves", r.curves);
        v("parameters", r.parameters);
        v("fit_time_ms", r.fit_time_ms);
        v("profile", r.profile);
        v("profile_time_ms", r.profile_time_ms);
        v("wheel", r.wheel, kSince);  // not saved before: such a file reads with no name
        v("message", r.message);
        v("data_issues", r.data_issues);
        v("start_description", r.start_description);
    }
};

template <>
struct Fields<id::StreamEstimate> {
    template <typename V>
    static void visit(V& v, id::StreamEstimate& e) {
        v("index", e.index);
        v("estimated", e.estimated);
        v("initialised", e.initialised);
        v("refitted", e.refitted);
        v("parameters", e.parameters);
        v("std", e.std);
        v("nis", e.nis);
        v("channels", e.channels);
        v("used", e.used);
        v("cusum", e.cusum);
        v("change_detected", e.change_detected);
        v("change_rejected", e.change_rejected);
        v("change_statistic", e.change_statistic);
        v("change_at", e.change_at);
        v("update_ms", e.update_ms);
    }
};

template <>
struct Fields<analysis::StreamFrame> {
    template <typename V>
    static void visit(V& v, analysis::StreamFrame& f) {
        v("estimate", f.estimate);
        v("parameters", f.parameters);
        v("time_s", f.time_s);
        v("fx_measured_n", f.fx_measured_n);
        v("fx_predicted_n", f.fx_predicted_n);
    }
};

template <>
struct Fields<SavedStream> {
    template <typename V>
    static void visit(V& v, SavedStream& s) {
        v("frames", s.frames);
        v("sample_count", s.sample_count);
        v("true_border", s.true_border);
        v("description", s.description);
        v("warnings", s.warnings);
        v("truth", s.truth);
        v("stopped", s.stopped);
    }
};

}  // namespace terra::project::saved

namespace terra::project {

using nlohmann::json;
namespace id = identification;

json savedJson(const id::IdentificationReport& report) { return saved::fieldsJson(report); }

id::IdentificationReport identificationReportFromJson(const json& j) {
    return saved::fieldsFrom<id::IdentificationReport>(j);
}

json saved::Value<id::IdentificationReport>::write(const id::IdentificationReport& report) {
    return fieldsJson(report);
}

void saved::Value<id::IdentificationReport>::read(const json& j, id::IdentificationReport& report) {
    report = fieldsFrom<id::IdentificationReport>(j);
}

json savedJson(const analysis::IdentificationResult& r) { return saved::fieldsJson(r); }

Result<analysis::IdentificationResult> identificationResultFromJson(const json& j,
                                                                    const std::string& where) {
    try {
        analysis::IdentificationResult r = saved::fieldsFrom<analysis::IdentificationResult>(j);
        // A saved result with a message had nothing to fit (a cancelled fit is never saved).
        if (!r.message.empty()) r.status = analysis::Outcome::Status::kInvalidInput;
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

json savedJson(const SavedStream& s) { return saved::fieldsJson(s); }

Result<SavedStream> savedStreamFromJson(const json& j, const std::string& where) {
    try {
        SavedStream s = saved::fieldsFrom<SavedStream>(j);
        if (s.frames.size() > s.sample_count)
            return std::vector<Issue>{{where, std::to_string(s.frames.size()) + " frames for " +
                                                  std::to_string(s.sample_count) + " samples"}};
        return s;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace terra::project
