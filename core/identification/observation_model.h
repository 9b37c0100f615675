#pragma once
/// @file observation_model.h
/// What the full wheel model (core/contact/wheel_forces.h) predicts for each sample of a data set,
/// and the weighted residuals and their exact derivatives that the identification minimises.
///
/// Two ways to know the contact:
/// - **entry angle** θ_f measured per sample: F_x, F_z, M_y follow from (s, β, θ_f) directly;
/// - **load** W known per sample (a `W_N` column, one value for all, or the measured F_z): θ_f is
///   the root of F_z(θ_f, θ) = W (section 2.6.1) inside every residual, differentiated exactly by
///   the implicit function theorem, dθ_f/dθ = −(∂F_z/∂θ)/(∂F_z/∂θ_f), with ∂F_z/∂θ and
///   ∂F_z/∂θ_f from one ceres::Jet evaluation at the root. F_z = W there by construction, so the
///   channels are F_x, M_y and the sinkage h = r (1 − cos θ_f) (Eq. 2.12; times 1 + S s with
///   Lyasko's slip sinkage, Eq. S.1) when measured.
/// θ_r = 0 as in Table 5.2.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "core/identification/data_set.h"
#include "core/identification/parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// The measured quantities a residual can compare.
enum Channel { kFxChannel, kFzChannel, kMyChannel, kSinkageChannel, kChannelCount };

/// Column names of the channels: "Fx_N", "Fz_N", "My_Nm", "sinkage_m".
const std::array<const char*, kChannelCount>& channelNames();

/// Per-channel values (noise levels, errors) [N, N, N·m, m].
using ChannelValues = std::array<double, kChannelCount>;

/// Where θ_f comes from.
enum class DataSource {
    kAuto,        ///< the entry angle when the data have it, else the load
    kEntryAngle,  ///< measured θ_f (entry_angle_deg or entry_angle_rad)
    kLoad,        ///< θ_f solved from the load W
};

/// How a data set is read by the model.
struct ModelSetup {
    DataSource source = DataSource::kEntryAngle;  ///< resolved: kEntryAngle or kLoad
    std::array<bool, kChannelCount> channels{};   ///< the residual channels
    std::vector<double> loads_n;  ///< W per sample: the F_z measurement (entry angle) or the load
    /// j_max [m] (+inf for none) of the options: the model takes it from the parameters
    /// (kJmax), this is what a caller held it at.
    double max_shear_deformation_m = 0.0;
    /// j_max is estimated: the Jacobian gets its column (a central difference; zero when held).
    bool max_shear_deformation_free = false;
    /// n₁ of Ding's slip-dependent exponent N = n + n₁ s (docs/model.md, "Slip-sinkage"), held
    /// fixed (not estimated); 0: the thesis model's constant n.
    double sinkage_exponent_slip = 0.0;
    /// S of Lyasko's slip sinkage h = r (1 − cos θ_f)(1 + S s) (docs/model.md, Eq. S.1), held
    /// fixed (a caller profiles it); 0: the thesis model's h. It scales the sinkage channel only.
    double slip_sinkage_coefficient = 0.0;
    /// The wheel model that predicts the forces: the full model's integrals (the default) or the
    /// quadratic approximation's closed forms (Eqs. 2.41–2.46), the rover's `"model":
    /// "quadratic"` — an estimator on board fits the model its planner uses (docs/traction.md
    /// §8). Both are linear in (K_s, c, K_s tan φ) at a given θ_f, so the screening's variable
    /// projection holds for either.
    contact::ContactModel model = contact::ContactModel::kFull;
    /// How the full model's integrals are evaluated: the default adaptive rule, or the Gauss rule
    /// alone (IntegrationOptions::gauss_only) for the search's screening and descents, which the
    /// refinement on the default rule finishes (docs/identification.md §9, "fourth pass").
    contact::IntegrationOptions integration{};
    std::string description;  ///< "entry angle; channels Fx_N, Fz_N, My_Nm"
};

/// The forces of the setup's model at `op` (contact::computeForces with its integration, or
/// computeQuadraticForces).
template <typename T>
contact::WheelForces<T> modelForces(const contact::ContactParameters<T>& p,
                                    const contact::OperatingPoint<T>& op, const ModelSetup& setup) {
    return setup.model == contact::ContactModel::kQuadratic
               ? contact::computeQuadraticForces(p, op)
               : contact::computeForces(p, op, contact::BulldozingModel::kBekker,
                                        setup.integration);
}

/// Resolves the setup. W per sample is the `W_N` cell, else `load_n`, else the measured F_z. With
/// the entry angle, F_z is a channel when measured or when a load is known (F_z = W); with the
/// load, F_x, M_y and the sinkage are. Issues name what is missing (no θ_f and no load, no
/// channel).
Result<ModelSetup> setupModel(const DataSet& data, DataSource source, std::optional<double> load_n,
                              double max_shear_deformation_m, double sinkage_exponent_slip = 0.0,
                              double slip_sinkage_coefficient = 0.0,
                              contact::ContactModel model = contact::ContactModel::kFull);

/// The model's prediction for one sample.
struct Prediction {
    bool ok = false;  ///< false: the soil cannot carry the load (no entry angle solves F_z = W)
    double entry_angle_rad = 0.0;
    ChannelValues values{};  ///< F_x, F_z, M_y, sinkage
};

/// The model of one data set; samples are referred to by index.
class ObservationModel {
public:
    /// Throws std::invalid_argument for an invalid wheel or a setup that does not match the data.
    ObservationModel(const DataSet& data, const wheel::WheelParameters& wheel, ModelSetup setup);

    const ModelSetup& setup() const { return setup_; }
    std::size_t size() const { return samples_.size(); }
    const Sample& sample(std::size_t i) const { return samples_[i]; }
    /// The channels compared for sample i (the setup's, less a sinkage the row does not have).
    std::array<bool, kChannelCount> channels(std::size_t i) const;
    int residualCount(std::size_t i) const;
    /// The measured value of a channel of sample i.
    double measured(std::size_t i, Channel c) const;

    /// The prediction at SI parameters p.
    Prediction predict(std::size_t i, const ParameterVector& p) const;

    /// Residuals (predicted − measured)/σ of sample i's channels at solver coordinates u
    /// (parameters.h), and, when `jacobian` is not null, their derivatives ∂r/∂u (row-major,
    /// residualCount(i) × kFullParameterCount). False when the load cannot be carried. Keeps the
    /// last θ_f of each sample as the next solve's start (not thread-safe).
    ///
    /// A sample with a slip of standard error σ_s (`Sample::slip_std`, errors in variables)
    /// has residuals of covariance I + σ_s² g gᵀ, g = ∂r/∂s (slipSlope over σ): r and the
    /// Jacobian come whitened by its inverse square root W = I − α ĝ ĝᵀ,
    /// α = 1 − 1/√(1 + σ_s² |g|²), so that ‖r‖² = eᵀ (I + σ_s² g gᵀ)⁻¹ e (W taken as a constant
    /// of u in the Jacobian; docs/identification.md §8, "An uncertain slip").
    bool residuals(std::size_t i, const double* u, const ChannelValues& sigma, double* r,
                   double* jacobian) const;

    /// ∂(prediction)/∂s of sample i's channels at SI parameters p [channel units per unit of
    /// slip], exact (a Jet along s); with θ_f solved from the load, through
    /// dθ_f/ds = −(∂F_z/∂s)/(∂F_z/∂θ_f), so the F_z entry is 0. nullopt when the load cannot be
    /// carried.
    std::optional<ChannelValues> slipSlope(std::size_t i, const ParameterVector& p) const;

private:
    // predict; with θ_f solved from the load, `by_angle` (if given) gets ∂(F_x, F_z, M_y)/∂θ_f
    // at the root when the solve's last Jet was there (Newton), else is left empty.
    Prediction predictAt(std::size_t i, const ParameterVector& p,
                         std::optional<std::array<double, 3>>* by_angle) const;
    // slipSlope at the entry angle θ_f; `by_angle` ∂(F_x, F_z, M_y)/∂θ_f when the caller has
    // them (else one more Jet evaluation along θ_f). nullopt when ∂F_z/∂θ_f ≤ 0.
    std::optional<ChannelValues> slipSlopeAt(std::size_t i, const ParameterVector& p,
                                             double entry_angle_rad,
                                             const std::array<double, 3>* by_angle) const;
    std::array<double, 3> shearLimitDerivative(std::size_t i, const ParameterVector& p,
                                               double entry_angle_rad) const;

    std::vector<Sample> samples_;
    wheel::WheelParameters wheel_;
    ModelSetup setup_;
    mutable std::vector<double> last_entry_angle_;  // warm starts of the θ_f solves
};

}  // namespace terra::identification
