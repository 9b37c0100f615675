#pragma once
/// @file soil_curves.h
/// The two curves of the soil alone (no slip), beside the forces panel's sweeps: bulldozing
/// resistance against sinkage (thesis Fig. 2.15; Eqs. 2.26–2.30 as corrected in docs/model.md,
/// E1) and static sinkage against load (Fig. 2.6; Eq. 2.7 and Bekker's Eq. 2.8 as corrected, E2).
/// The studio's forces panel and a script's "soil-curves" analysis.

#include "core/analysis/analysis.h"
#include "core/common/table.h"

namespace terra::analysis {

struct AnalysisType;

struct SoilCurvesSettings {
    int points = 61;  ///< grid size of each curve
    /// Largest sinkage of the bulldozing curve as a fraction of r (0.5: θ_f = 60°).
    double max_sinkage_fraction_of_radius = 0.5;
    /// Largest load of the static-sinkage curve as a multiple of the conditions' W.
    double max_load_factor = 2.0;

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson and
    /// compute's checks.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

template <typename Visitor>
void SoilCurvesSettings::visitFields(Visitor& v) {
    v(fields::integer("points", points, 2, 10000, "grid size of each curve"));
    v(fields::number("max_sinkage_fraction_of_radius", max_sinkage_fraction_of_radius,
                     {0.0, 1.0, true, false}, "",
                     "largest sinkage of the bulldozing curve as a fraction of r"));
    v(fields::number(
        "max_load_factor", max_load_factor, {0.0, 100.0, true, false}, "",
        "largest load of the static-sinkage curve as a multiple of the conditions' W"));
}

/// The keys of SoilCurvesSettings::visitFields, read strictly (io::readFields): "points"
/// [2, 10000], "max_sinkage_fraction_of_radius" (0, 1], "max_load_factor" (0, 100].
void readSoilCurvesSettings(io::ObjectReader& r, SoilCurvesSettings& out);
/// The settings' file keys (io::fieldsToJson).
nlohmann::json toJson(const SoilCurvesSettings& settings);

struct SoilCurves {
    /// sinkage_mm, entry_angle_deg, Fb_bekker_N, Fb_hegedus_N: F_b of one side wall over the
    /// submerged segment at θ_f = acos(1 − h/r), with the Bekker and the Hegedus coefficients
    /// (Eq. 2.27). The forces' F_s uses Bekker's.
    Table bulldozing;
    /// load_N, h_bekker_mm (Eq. 2.8, E2), h_eq27_mm (Eq. 2.7 over −θ_s..θ_s, as printed),
    /// h_eq27_front_mm (Eq. 2.7 over 0..θ_s, Bekker's assumption). NaN where Eq. 2.7 has no
    /// equilibrium (the wheel would sink to its axle).
    Table static_sinkage;
    double load_n = 0.0;  ///< the conditions' W [N], marked on the static-sinkage plot
    bool cancelled = false;
};

/// Both curves (partial tables when cancelled). Throws std::invalid_argument for invalid inputs
/// or settings (a struct built in code is checked as its reader would read it: io::fieldIssues).
SoilCurves computeSoilCurves(const Inputs& inputs, const SoilCurvesSettings& settings = {},
                             const Control& control = {});
/// Tables "static_sinkage" (main) and "bulldozing".
Outcome soilCurvesOutcome(SoilCurves curves);

AnalysisType soilCurvesType();

}  // namespace terra::analysis
