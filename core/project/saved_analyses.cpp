#include "core/project/saved_analyses.h"

#include <stdexcept>

#include "core/io/parameters_json.h"
#include "core/project/result_json.h"
#include "core/project/saved_validation.h"

namespace terra::project::saved {

// The key lists: one per struct, for writing and reading.

template <>
struct Fields<contact::ApproximationError> {
    template <typename V>
    static void visit(V& v, contact::ApproximationError& e) {
        v("rmse", e.rmse);
        v("mae", e.mae);
    }
};

template <>
struct Fields<analysis::StressResult> {
    template <typename V>
    static void visit(V& v, analysis::StressResult& r) {
        v("table", r.table);
        v("errors", r.errors);
        v("entry_angle_deg", r.entry_angle_deg);
        v("max_stress_angle_deg", r.max_stress_angle_deg);
        v("message", r.message);
    }
};

template <>
struct Fields<analysis::SweepResult> {
    template <typename V>
    static void visit(V& v, analysis::SweepResult& r) {
        v("table", r.table);
        v("warnings", r.warnings);
        v("cancelled", r.cancelled);
    }
};

template <>
struct Fields<analysis::SensitivityResult> {
    template <typename V>
    static void visit(V& v, analysis::SensitivityResult& r) {
        v("family", r.family);
        v("parameter_keys", r.parameter_keys);
        v("tornado", r.tornado);
        v("tornado_keys", r.tornado_keys);
    }
};

template <>
struct Fields<analysis::SoilCurves> {
    template <typename V>
    static void visit(V& v, analysis::SoilCurves& c) {
        v("bulldozing", c.bulldozing);
        v("static_sinkage", c.static_sinkage);
        v("load_n", c.load_n);
        v("cancelled", c.cancelled);
    }
};

template <>
struct Fields<SavedTestSweep> {
    template <typename V>
    static void visit(V& v, SavedTestSweep& s) {
        v("load_n", s.load_n);
        v("table", s.table);
    }
};

/// The comparison with the test in its own saved form (saved_validation.h).
template <>
struct Value<analysis::ValidationResult> {
    static nlohmann::json write(const analysis::ValidationResult& r) { return savedJson(r); }
    static void read(const nlohmann::json& json, analysis::ValidationResult& r) {
        Result<analysis::ValidationResult> read = validationResultFromJson(json, "validation");
        if (!read) throw std::invalid_argument(read.message());
        r = std::move(read).value();
    }
};

template <>
struct Fields<SavedForces> {
    template <typename V>
    static void visit(V& v, SavedForces& f) {
        v("sweep", f.sweep);
        v("soil", f.soil);
        v("validation", f.validation);
        v("test_sweeps", f.test_sweeps);
    }
};

template <>
struct Fields<contact::WheelForces<double>> {
    template <typename V>
    static void visit(V& v, contact::WheelForces<double>& f) {
        v("fx", f.fx);
        v("fy", f.fy);
        v("fz", f.fz);
        v("mx", f.mx);
        v("my", f.my);
        v("mz", f.mz);
        v("fb", f.fb);
        v("fs", f.fs);
    }
};

template <>
struct Fields<compaction::StressMeasures> {
    template <typename V>
    static void visit(V& v, compaction::StressMeasures& m) {
        v("sigma_z", m.sigma_z);
        v("sigma_x", m.sigma_x);
        v("sigma_y", m.sigma_y);
        v("mean", m.mean);
        v("major", m.major);
    }
};

template <>
struct EnumLast<compaction::Risk> {
    static constexpr compaction::Risk value = compaction::Risk::kRed;
};

template <>
struct Fields<analysis::DepthValues> {
    template <typename V>
    static void visit(V& v, analysis::DepthValues& d) {
        v("depth_m", d.depth_m);
        v("max", d.max);
        v("precompression_pa", d.precompression_pa);
        v("risk", d.risk);
    }
};

template <>
struct Fields<analysis::CompactionPass> {
    template <typename V>
    static void visit(V& v, analysis::CompactionPass& p) {
        v("pass", p.pass);
        v("entry_angle_deg", p.entry_angle_deg);
        v("sinkage_m", p.sinkage_m);
        v("sinkage_increment_m", p.sinkage_increment_m);
        v("rut_depth_m", p.rut_depth_m);
        v("forces", p.forces);
        v("profile", p.profile);
        v("red_to_depth_m", p.red_to_depth_m);
        v("bulk_density_kg_m3", p.bulk_density_kg_m3);
        v("precompression_pa", p.precompression_pa);
    }
};

/// The profile used, in its file form (core/io/parameters_json.h).
template <>
struct Value<soil::SoilProfile> {
    static nlohmann::json write(const soil::SoilProfile& p) { return io::toJson(p); }
    static void read(const nlohmann::json& json, soil::SoilProfile& p) {
        Result<soil::SoilProfile> read = io::profileFromJson(json, "profile");
        if (!read) throw std::invalid_argument(read.message());
        p = std::move(read).value();
    }
};

template <>
struct Fields<analysis::CompactionResult> {
    template <typename V>
    static void visit(V& v, analysis::CompactionResult& r) {
        v("passes", r.passes);
        v("envelope", r.envelope);
        v("red_to_depth_m", r.red_to_depth_m);
        v("profile", r.profile);
        v("map", r.map);
        v("load_n", r.load_n);
        v("concentration_used", r.concentration_used);
        v("message", r.message);
        v("cancelled", r.cancelled);
        v("notes", r.notes);
    }
};

}  // namespace terra::project::saved

namespace terra::project {
namespace {

/// fieldsFrom<T>, every problem as an Issue under `where`.
template <typename T>
Result<T> readSaved(const nlohmann::json& json, const std::string& where) {
    try {
        return saved::fieldsFrom<T>(json);
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace

nlohmann::json savedJson(const SavedForces& forces) { return saved::fieldsJson(forces); }
nlohmann::json savedJson(const analysis::StressResult& result) { return saved::fieldsJson(result); }
nlohmann::json savedJson(const analysis::CompactionResult& result) {
    return saved::fieldsJson(result);
}
nlohmann::json savedJson(const analysis::SensitivityResult& result) {
    return saved::fieldsJson(result);
}

Result<SavedForces> savedForcesFromJson(const nlohmann::json& json, const std::string& where) {
    return readSaved<SavedForces>(json, where);
}

Result<analysis::StressResult> stressResultFromJson(const nlohmann::json& json,
                                                    const std::string& where) {
    return readSaved<analysis::StressResult>(json, where);
}

Result<analysis::CompactionResult> compactionResultFromJson(const nlohmann::json& json,
                                                            const std::string& where) {
    Result<analysis::CompactionResult> read = readSaved<analysis::CompactionResult>(json, where);
    if (!read) return read;
    // Every pass's profile and the envelope at the same depths, the densities one per layer.
    const analysis::CompactionResult& r = *read;
    for (const analysis::CompactionPass& p : r.passes) {
        const bool layers = !r.profile || p.bulk_density_kg_m3.empty() ||
                            p.bulk_density_kg_m3.size() == r.profile->layers.size();
        if (p.profile.size() != r.envelope.size() || !layers)
            return std::vector<Issue>{
                {where, "pass " + std::to_string(p.pass) + " does not match the envelope"}};
    }
    return read;
}

Result<analysis::SensitivityResult> sensitivityResultFromJson(const nlohmann::json& json,
                                                              const std::string& where) {
    return readSaved<analysis::SensitivityResult>(json, where);
}

}  // namespace terra::project
