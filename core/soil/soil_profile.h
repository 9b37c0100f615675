#pragma once
/// @file soil_profile.h
/// A soil profile for compaction: layers by depth, each with what decides its strength (the
/// precompression stress σ_pc, given or from a pedotransfer function), its stress concentration
/// factor ν and its compression law (docs/compaction.md, "Soil profile"). SI inside; the file
/// keys carry the published units (kPa, Mg/m³, hPa, kg/kg).

#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"

namespace terra::soil {

/// The compression law of a layer (O'Sullivan & Robertson 1996; O'Sullivan et al. 1999, as
/// implemented in the R package soilphysics, `soilDeformation`): specific volume v = ρ_s/ρ_b
/// against ln p (p in kPa) — virgin compression line v = N − λ ln p, recompression κ, a yield
/// line m below the VCL joined by a steeper recompression κ′ (m = 0, κ′ = κ: the plain model).
struct CompressionLaw {
    /// N [-]: v on the VCL at p = 1 kPa. Empty: the VCL is placed through the layer's state at
    /// its precompression stress (docs/compaction.md, K2).
    std::optional<double> virgin_n;
    double lambda = 0.05;               ///< λ [-]: slope of the VCL against ln p
    double kappa = 0.005;               ///< κ [-]: slope of the recompression (and rebound) line
    std::optional<double> kappa_steep;  ///< κ′ [-]; empty: κ
    double yield_offset = 0.0;          ///< m [ln kPa]: the yield line lies λ m below the VCL
};

/// One layer of a profile.
struct SoilLayer {
    double top_m = 0.0;                         ///< [m] below the surface
    double bottom_m = 0.3;                      ///< [m], > top
    std::optional<double> clay_kg_kg;           ///< clay content C [kg/kg] (a fraction)
    double bulk_density_kg_m3 = 1500.0;         ///< ρ_b [kg/m³] (file: Mg/m³)
    std::optional<double> matric_suction_pa;    ///< h [Pa] (file: hPa)
    std::optional<double> precompression_pa;    ///< σ_pc [Pa] given directly (file: kPa)
    std::optional<double> concentration;        ///< ν [-] of this layer
    double particle_density_kg_m3 = 2650.0;     ///< ρ_s [kg/m³] (file: Mg/m³)
    std::optional<CompressionLaw> compression;  ///< empty: the density is not followed
};

/// A profile: contiguous layers from the surface down.
struct SoilProfile {
    std::string name;
    std::string source;
    std::vector<SoilLayer> layers;

    /// The layer holding depth z (the upper one at a boundary); nullptr below the last layer.
    const SoilLayer* layerAt(double depth_m) const;
    /// Index of that layer, or −1.
    int layerIndexAt(double depth_m) const;
};

/// Every problem of a profile, each naming the layer ("layers[1].clay_kg_kg") with the value and
/// the allowed range: no layers; a layer whose top is not the previous bottom (overlap or gap) or
/// the first not at 0; clay outside [0, 1] (with a hint when it looks like a percentage); bulk
/// or particle density, suction, σ_pc, ν or compression parameters out of range; neither σ_pc
/// nor (clay and suction) given.
std::vector<Issue> validate(const SoilProfile& profile, const std::string& prefix = "profile");

/// σ_pc [Pa] of Schjønning & Lamandé (2018, Geoderma 320:115–125), as implemented in the R
/// package soilphysics (`soilStrength2`): √σ_pc[kPa] = −26.51 + 25.57 ρ_b[Mg/m³] − 20.40 C
/// + 10.26 C pF, pF = log₁₀(h[hPa]), C [kg/kg]; a negative root gives 0. Inputs in SI.
double precompressionStress(double clay_kg_kg, double bulk_density_kg_m3, double matric_suction_pa);

/// The layer's σ_pc [Pa]: given, or from the pedotransfer function.
double precompressionStress(const SoilLayer& layer);

/// Bulk density [kg/m³] after a largest stress `stress_pa` (O'Sullivan's model; docs/compaction.md,
/// K1–K3), from the layer's current density, its law and its precompression stress. Unchanged
/// when the layer has no compression law or the stress stays below yield.
double compactedDensity(const SoilLayer& layer, double stress_pa);

/// The same, from explicit values (ρ_s, ρ_b, law with N set, p in Pa): the published model.
double compactedDensity(double particle_density_kg_m3, double bulk_density_kg_m3,
                        const CompressionLaw& law, double stress_pa);

}  // namespace terra::soil
