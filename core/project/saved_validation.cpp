#include "core/project/saved_validation.h"

#include <stdexcept>

#include "core/io/parameters_json.h"
#include "core/project/result_json.h"
#include "core/project/saved_identification.h"

namespace terra::project::saved {

/// A soil as its own file format (core/io/parameters_json.h).
template <>
struct Value<soil::SoilParameters> {
    static nlohmann::json write(const soil::SoilParameters& soil) { return io::toJson(soil); }
    static void read(const nlohmann::json& json, soil::SoilParameters& soil) {
        Result<soil::SoilParameters> read = io::soilFromJson(json, "soil");
        if (!read) throw std::invalid_argument(read.message());
        soil = read.value();
    }
};

template <>
struct Fields<analysis::ChannelMetrics> {
    template <typename V>
    static void visit(V& v, analysis::ChannelMetrics& m) {
        v("count", m.count);
        v("rmse", m.rmse);
        v("mae", m.mae);
        v("max_rel_error", m.max_rel_error);
    }
};

template <>
struct Fields<analysis::PointComparison> {
    template <typename V>
    static void visit(V& v, analysis::PointComparison& p) {
        v("load_n", p.point.load_n);
        v("slip", p.point.slip);
        v("slip_angle_deg", p.point.slip_angle_deg);
        v("measured", p.point.measured);
        v("line", p.point.line);
        v("predicted", p.predicted);
        v("failure", p.failure);
        v("entry_angle_deg", p.entry_angle_deg);
        v("values", p.values);
        v("in_fit", p.in_fit);
    }
};

template <>
struct Fields<analysis::ValidationRun> {
    template <typename V>
    static void visit(V& v, analysis::ValidationRun& run) {
        v("soil", run.soil);
        v("points", run.points);
        v("metrics", run.metrics);
        v("curves", run.curves);
    }
};

template <>
struct Fields<analysis::Calibration> {
    template <typename V>
    static void visit(V& v, analysis::Calibration& c) {
        v("report", c.report);
        v("prior", c.prior);
        v("channels", c.channels);
        v("soil", c.soil);
        v("n1", c.n1);
        v("n1_std", c.n1_std);
        v("n1_profile", c.n1_profile);
        v("slip_sinkage", c.slip_sinkage);
        v("slip_sinkage_std", c.slip_sinkage_std);
        v("slip_sinkage_profile", c.slip_sinkage_profile);
        v("after", c.after);
        v("held_out_before", c.held_out_before);
        v("held_out", c.held_out);
    }
};

/// What a validation computed; its status is derived on reading (below).
template <>
struct Fields<analysis::ValidationResult> {
    template <typename V>
    static void visit(V& v, analysis::ValidationResult& r) {
        v("source", r.source);
        v("wheel", r.wheel, kSince);  // not saved before: such a file reads with no name
        v("before", r.before);
        v("calibration", r.calibration);
        v("notes", r.notes);
    }
};

}  // namespace terra::project::saved

namespace terra::project {

using nlohmann::json;

json savedJson(const analysis::ValidationResult& r) { return saved::fieldsJson(r); }

Result<analysis::ValidationResult> validationResultFromJson(const json& j,
                                                            const std::string& where) {
    try {
        analysis::ValidationResult r = saved::fieldsFrom<analysis::ValidationResult>(j);
        // Its status as computed (a saved result is never cancelled nor an invalid input).
        r.soil = r.before.soil.name;
        r.message = analysis::validationFailure(r);
        if (!r.message.empty()) r.status = analysis::Outcome::Status::kFailed;
        return r;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace terra::project
