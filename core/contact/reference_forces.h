#pragma once
/// @file reference_forces.h
/// An independent, slow, high-accuracy evaluation of the contact integrals (Eqs. 2.23–2.35) with
/// Boost's adaptive tanh-sinh or Gauss–Kronrod quadrature directly in θ, split at θ_m, at every
/// kink, at θ = 0 (where the shear direction turns at small β), and into sub-pieces of at most
/// 0.1 rad (at least four per segment). Double exponential (tanh-sinh) quadrature copes with the
/// endpoint singularities of σ on its own and clusters its nodes at the split points, so this
/// shares no numerical idea with computeForces() (no end mapping, no scale splits); the tests use
/// it as the truth. Safe in Debug builds (no Boost assertion fires on narrow pieces).

#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/wheel_forces.h"

namespace terra::contact {

/// The adaptive quadrature used by computeForcesReference().
enum class ReferenceMethod {
    kTanhSinh,      ///< double-exponential, handles endpoint singularities
    kGaussKronrod,  ///< adaptive 61-point Gauss–Kronrod
};

/// The full model's forces by adaptive quadrature to relative tolerance `tolerance`.
WheelForces<double> computeForcesReference(const ContactParameters<double>& p,
                                           const OperatingPoint<double>& op,
                                           BulldozingModel bulldozing = BulldozingModel::kBekker,
                                           ReferenceMethod method = ReferenceMethod::kTanhSinh,
                                           double tolerance = 1e-12);

}  // namespace terra::contact
