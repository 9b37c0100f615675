#pragma once
/// @file screening.h
/// Internal (identify.cpp): the cheap first pass of the global search. A space-filling design over
/// the parameter box, and the variable projection that makes it cheap when θ_f is measured: at
/// fixed θ_f the normal stress is K_s times a function of (a₀, a₁, n) (Eqs. 2.17, 2.19) and the
/// shear stress is (c + σ tan φ) times a function of K (Eqs. 2.20–2.22), so F_x, F_z, M_y are
/// linear in α = (K_s, c, K_s tan φ):
///   F = K_s P(a₀, a₁, n) + c Q(a₀, a₁, K) + K_s tan φ R(a₀, a₁, n, K).
/// For given (a₀, a₁, n, K), α is the bounded linear least-squares solution (K_s, c in their
/// bounds, tan φ_min ≤ α₃/α₁ ≤ tan φ_max): only four parameters are sampled, and the c–φ and
/// K_s direction of the search disappear.

#include <functional>
#include <vector>

#include "core/identification/fit_problem.h"

namespace terra::identification::detail {

/// Projects the linear parameters for the entry-angle model on a set of samples.
class LinearProjection {
public:
    LinearProjection(const Objective& objective, std::vector<std::size_t> samples,
                     const wheel::WheelParameters& wheel);

    /// Replaces K_s, c, φ of p (unless fixed) by their bounded least-squares values for p's a₀,
    /// a₁, n, K and returns the χ² on the samples (data, and the priors of the nonlinear
    /// parameters and of K_s and c; a prior on φ is left to the refinement). +inf on failure.
    double project(ParameterVector& p) const;

    /// The projected problem as a cost function of the 7 solver coordinates u, of which only a₀,
    /// a₁, n and ln K matter (hold the others): residuals at the projected α, and Kaufman's
    /// Jacobian P⊥ ∂F/∂θ (the variable-projection Jacobian without its second-order term), P⊥ the
    /// projector onto the complement of the linear parameters' columns on the active face.
    /// Owned by the caller; `this` must outlive it.
    ceres::CostFunction* costFunction() const;

private:
    struct Linearised;
    class Cost;
    bool linearise(const ParameterVector& p, Linearised& out) const;
    /// body(t) for every t < samples_.size(), on the objective's pool when it has one.
    void forSamples(const std::function<void(std::size_t)>& body) const;

    const Objective& objective_;
    std::vector<std::size_t> samples_;
    wheel::WheelParameters wheel_;
    int data_rows_ = 0;
    std::vector<std::size_t> first_row_;  // each sample's first data row
};

/// `count` points of a Halton sequence (bases 2, 3, 5, …) over the dimensions marked in `vary`,
/// in solver coordinates uniformly over `box`, shifted (Cranley–Patterson) by a seeded random
/// vector; the other dimensions keep `base`'s values.
std::vector<ParameterVector> haltonDesign(int count,
                                          const std::array<bool, kFullParameterCount>& vary,
                                          const DesignBox& box, const ParameterVector& base,
                                          std::uint64_t seed);

}  // namespace terra::identification::detail
