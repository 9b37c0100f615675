#include "core/identification/screening.h"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <algorithm>
#include <bit>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <cmath>
#include <functional>

#include "core/common/worker_pool.h"
#include "core/contact/wheel_forces.h"

namespace terra::identification::detail {
namespace {

// The linear parameters are solved for in units of order one: K_s and K_s tan φ in MPa/m^n, c in
// kPa.
constexpr double kModulusUnit = 1e6, kCohesionUnit = 1e3;
// Nominal values of (K_s, c, φ) at which the adaptive integrator judges its pieces for the basis
// (any values give the same basis up to the quadrature error; realistic ones keep its splits
// realistic; on the Gauss rule they do not matter), and at which the quadratic model's Jet is
// taken.
constexpr double kNominalModulus = 1e6, kNominalCohesion = 1e3, kNominalFriction = 0.5;

// min ½ αᵀGα − bᵀα subject to C α = e (equalities) and A α ≤ d (inequalities), three unknowns.
// On a face of the feasible polytope (a set of active inequalities held as equalities) the
// minimiser and the multipliers μ solve the KKT system [G Cᵀ; C 0] (α, μ) = (b, e). The problem
// is convex, so the KKT conditions are sufficient: the first face, by increasing number of active
// inequalities, whose minimiser is feasible and whose active multipliers are non-negative holds
// the minimum. Should rounding leave no face passing that test, the best feasible minimiser of
// all faces is the answer, as it was before this rule. Where the minimiser is not unique (G
// singular: a tiny n) or a multiplier is zero, the face found first may differ from the one the
// best-value rule picked (the same value; α and its face, which shapes the Kaufman Jacobian, may
// differ): on the 144 cells of the identification matrix it made no difference.
struct SmallQp {
    Eigen::Matrix3d g;
    Eigen::Vector3d b;
    std::vector<Eigen::RowVector3d> eq_rows;
    std::vector<double> eq_values;
    std::vector<Eigen::RowVector3d> in_rows;
    std::vector<double> in_values;

    // At most three rows on a face: the KKT system is at most 6 × 6, on the stack.
    using Kkt = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
    using KktVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

    struct OnFace {
        Eigen::Vector3d x;
        bool feasible = false;
        bool kkt = false;  // feasible, a stationary point of the face, active multipliers ≥ 0
    };

    OnFace solveOnFace(unsigned mask) const {
        OnFace out;
        const int equalities = static_cast<int>(eq_rows.size());
        const int m = equalities + std::popcount(mask);
        if (m > 3) return out;  // more rows than unknowns (and than Kkt's 6 × 6)
        Kkt kkt = Kkt::Zero(3 + m, 3 + m);
        KktVector rhs = KktVector::Zero(3 + m);
        kkt.topLeftCorner<3, 3>() = g;
        rhs.head<3>() = b;
        int row = 3;
        auto add = [&](const Eigen::RowVector3d& c, double value) {
            kkt.block<1, 3>(row, 0) = c;
            kkt.block<3, 1>(0, row) = c.transpose();
            rhs(row) = value;
            ++row;
        };
        for (int k = 0; k < equalities; ++k) add(eq_rows[k], eq_values[k]);
        for (std::size_t k = 0; k < in_rows.size(); ++k) {
            if (mask & (1u << k)) add(in_rows[k], in_values[k]);
        }
        // Complete orthogonal decomposition: with collinear columns (a tiny n makes K_s and
        // K_s tan φ nearly so) the KKT matrix is singular, and its minimum-norm solution is one
        // of the equally good minimisers.
        const KktVector z = kkt.completeOrthogonalDecomposition().solve(rhs);
        out.x = z.head<3>();
        if (!z.allFinite()) return out;
        for (std::size_t k = 0; k < in_rows.size(); ++k) {
            if (in_rows[k].dot(out.x) > in_values[k] + 1e-9 * (1.0 + std::abs(in_values[k])))
                return out;
        }
        out.feasible = true;
        if ((kkt * z - rhs).norm() > 1e-9 * (1.0 + rhs.norm())) return out;
        for (int r = 3 + equalities; r < 3 + m; ++r) {
            if (z(r) < -1e-10) return out;
        }
        out.kkt = true;
        return out;
    }

    // The minimum and the rows that hold on its face (equalities and active inequalities).
    bool solve(Eigen::Vector3d& best, std::vector<Eigen::RowVector3d>& face) const {
        const int n = static_cast<int>(in_rows.size());
        const int room = 3 - static_cast<int>(eq_rows.size());
        const auto faceOf = [&](unsigned mask) {
            face = eq_rows;
            for (int k = 0; k < n; ++k) {
                if (mask & (1u << k)) face.push_back(in_rows[k]);
            }
        };
        double best_value = INFINITY;
        unsigned best_mask = 0;
        for (int count = 0; count <= std::min(room, n); ++count) {
            for (unsigned mask = 0; mask < (1u << n); ++mask) {
                if (std::popcount(mask) != count) continue;
                const OnFace f = solveOnFace(mask);
                if (f.kkt) {
                    best = f.x;
                    faceOf(mask);
                    return true;
                }
                if (!f.feasible) continue;
                const double value = 0.5 * f.x.dot(g * f.x) - b.dot(f.x);
                if (value < best_value) {
                    best_value = value;
                    best = f.x;
                    best_mask = mask;
                }
            }
        }
        if (!std::isfinite(best_value)) return false;
        faceOf(best_mask);
        return true;
    }
};

double radicalInverse(unsigned index, unsigned base) {
    double result = 0.0, fraction = 1.0 / base;
    while (index > 0) {
        result += fraction * (index % base);
        index /= base;
        fraction /= base;
    }
    return result;
}

}  // namespace

// The weighted rows of the projected least-squares problem at one point (a₀, a₁, n, K): data
// rows F ≈ Φ α, prior rows of K_s and c, the projected α and its face.
struct LinearProjection::Linearised {
    std::vector<Eigen::RowVector3d> rows;  // Φ, weighted (data rows first, then prior rows)
    std::vector<double> y;                 // targets, weighted
    Eigen::Vector3d alpha;                 // (K_s, c, K_s tan φ) in (MPa/m^n, kPa, MPa/m^n)
    std::vector<Eigen::RowVector3d> face;  // rows holding on the active face
    double nonlinear_prior = 0.0;          // Σ ((θ − mean)/std)² of a₀, a₁, n, K
};

LinearProjection::LinearProjection(const Objective& objective, std::vector<std::size_t> samples,
                                   const wheel::WheelParameters& wheel)
    : objective_(objective), samples_(std::move(samples)), wheel_(wheel) {
    for (std::size_t i : samples_) {
        first_row_.push_back(static_cast<std::size_t>(data_rows_));
        const auto active = objective_.model->channels(i);
        for (int c = 0; c < 3; ++c) data_rows_ += active[c];
    }
}

void LinearProjection::forSamples(const std::function<void(std::size_t)>& body) const {
    if (objective_.pool) {
        objective_.pool->forEachIndex(samples_.size(), body);
    } else {
        for (std::size_t t = 0; t < samples_.size(); ++t) body(t);
    }
}

bool LinearProjection::linearise(const ParameterVector& p, Linearised& out) const {
    using J = ceres::Jet<double, 3>;
    const ObservationModel& model = *objective_.model;
    const double tan0 = std::tan(kNominalFriction);
    const contact::ContactParameters<J> cp{J(wheel_.radius_m),
                                           J(wheel_.width_m),
                                           J(p[kN]),
                                           J(model.setup().sinkage_exponent_slip),
                                           J(kNominalModulus, 0),
                                           J(kNominalCohesion, 1),
                                           J(kNominalFriction, 2),
                                           J(p[kK]),
                                           J(0.0),
                                           J(p[kA0]),
                                           J(p[kA1]),
                                           p[kJmax],
                                           wheel_.lugShearOffset()};
    // Each sample's rows in their own place (first_row_), so that the samples can be shared
    // among the pool's threads; the same numbers whatever their count.
    out.rows.assign(static_cast<std::size_t>(data_rows_), Eigen::RowVector3d::Zero());
    out.y.assign(static_cast<std::size_t>(data_rows_), 0.0);
    // F = K_s P + c Q + K_s tan φ R: the full model's forms by one double stress evaluation per
    // node (contact::computeLinearForces); the quadratic model's by the Jet of the nominal α.
    const bool linear_forms = model.setup().model == contact::ContactModel::kFull;
    const contact::ContactParameters<double> shape = cp.cast<double>();  // K_s, c, φ unused
    const std::array<double, 3> nominal{kNominalModulus, kNominalCohesion, kNominalModulus * tan0};
    forSamples([&](std::size_t t) {
        const std::size_t i = samples_[t];
        const Sample& s = model.sample(i);
        std::array<std::array<double, 3>, 3> forms{};  // [F_x, F_z, M_y][P, Q, R]
        if (linear_forms) {
            const contact::LinearForces f = contact::computeLinearForces(
                shape,
                {s.slip, s.slip_angle_rad.value_or(0.0), s.entry_angle_rad, 0.0, std::nullopt},
                nominal, model.setup().integration);
            forms = {f.fx, f.fz, f.my};
        } else {
            const contact::OperatingPoint<J> op{J(s.slip), J(s.slip_angle_rad.value_or(0.0)),
                                                J(s.entry_angle_rad), J(0.0), std::nullopt};
            const contact::WheelForces<J> f = modelForces(cp, op, model.setup());
            const J* channel[3] = {&f.fx, &f.fz, &f.my};
            for (int c = 0; c < 3; ++c) {
                // ∂F/∂c = Q, ∂F/∂φ = K_s R / cos²φ, ∂F/∂K_s = P + tan φ R.
                const double r = channel[c]->v[2] * (1.0 / (kNominalModulus * (1.0 + tan0 * tan0)));
                forms[c] = {channel[c]->v[0] - tan0 * r, channel[c]->v[1], r};
            }
        }
        const auto active = model.channels(i);
        std::size_t row = first_row_[t];
        for (int c = 0; c < 3; ++c) {
            if (!active[c]) continue;
            const auto& [pk, q, r] = forms[c];
            const double w = 1.0 / objective_.sigma[c];
            out.rows[row] = {pk * kModulusUnit * w, q * kCohesionUnit * w, r * kModulusUnit * w};
            out.y[row] = model.measured(i, static_cast<Channel>(c)) * w;
            ++row;
        }
    });
    // Priors on K_s and c are rows of the linear problem; priors on a₀, a₁, n, K are constants.
    const Priors& priors = objective_.priors;
    const auto& fixed = objective_.fixed;
    const auto addPrior = [&](int k, int index, double unit) {
        if (!priors[k] || fixed[k]) return;
        const double w = unit / priors[k]->std;
        Eigen::RowVector3d row = Eigen::RowVector3d::Zero();
        row(index) = w;
        out.rows.push_back(row);
        out.y.push_back(w * priors[k]->mean / unit);
    };
    addPrior(kKs, 0, kModulusUnit);
    addPrior(kC, 1, kCohesionUnit);
    out.nonlinear_prior = 0.0;
    for (int k : {kA0, kA1, kN, kK, kJmax}) {
        if (priors[k] && !fixed[k])
            out.nonlinear_prior += std::pow((p[k] - priors[k]->mean) / priors[k]->std, 2);
    }
    SmallQp qp;
    qp.g = Eigen::Matrix3d::Zero();
    qp.b = Eigen::Vector3d::Zero();
    for (std::size_t r = 0; r < out.rows.size(); ++r) {
        qp.g += out.rows[r].transpose() * out.rows[r];
        qp.b += out.rows[r].transpose() * out.y[r];
    }
    // Scaled to a unit trace (the minimiser is the same): the KKT matrix then mixes the normal
    // equations and the constraint rows at one scale, so the active constraints hold to rounding.
    const double scale = qp.g.trace() > 0 ? 1.0 / qp.g.trace() : 1.0;
    qp.g = qp.g * scale + Eigen::Matrix3d::Identity() * 1e-12;
    qp.b *= scale;
    const ParameterBounds& bounds = objective_.bounds;
    const auto bound = [&](const Eigen::RowVector3d& row, double value) {
        qp.in_rows.push_back(row);
        qp.in_values.push_back(value);
    };
    const auto hold = [&](const Eigen::RowVector3d& row, double value) {
        qp.eq_rows.push_back(row);
        qp.eq_values.push_back(value);
    };
    if (fixed[kKs]) {
        hold({1, 0, 0}, p[kKs] / kModulusUnit);
    } else {
        bound({-1, 0, 0}, -bounds.lower[kKs] / kModulusUnit);
        bound({1, 0, 0}, bounds.upper[kKs] / kModulusUnit);
    }
    if (fixed[kC]) {
        hold({0, 1, 0}, p[kC] / kCohesionUnit);
    } else {
        bound({0, -1, 0}, -bounds.lower[kC] / kCohesionUnit);
        bound({0, 1, 0}, bounds.upper[kC] / kCohesionUnit);
    }
    if (fixed[kPhi]) {
        hold({std::tan(p[kPhi]), 0, -1}, 0.0);
    } else {
        bound({std::tan(bounds.lower[kPhi]), 0, -1}, 0.0);
        bound({-std::tan(bounds.upper[kPhi]), 0, 1}, 0.0);
    }
    return qp.solve(out.alpha, out.face);
}

double LinearProjection::project(ParameterVector& p) const {
    Linearised l;
    if (!linearise(p, l)) return INFINITY;
    p[kKs] = l.alpha(0) * kModulusUnit;
    p[kC] = l.alpha(1) * kCohesionUnit;
    p[kPhi] = std::atan2(l.alpha(2), l.alpha(0));
    double chi2 = l.nonlinear_prior;
    for (std::size_t r = 0; r < l.rows.size(); ++r)
        chi2 += std::pow(l.rows[r].dot(l.alpha) - l.y[r], 2);
    return chi2;
}

class LinearProjection::Cost final : public ceres::CostFunction {
public:
    explicit Cost(const LinearProjection& projection) : projection_(projection) {
        const Objective& o = projection_.objective_;
        for (int k : {kKs, kC}) alpha_priors_ += o.priors[k] && !o.fixed[k];
        for (int k : {kA0, kA1, kN, kK, kJmax}) {
            if (o.priors[k] && !o.fixed[k]) nonlinear_priors_.push_back(k);
        }
        shear_limit_ = !o.fixed[kJmax];
        set_num_residuals(projection_.data_rows_ + alpha_priors_ +
                          static_cast<int>(nonlinear_priors_.size()));
        mutable_parameter_block_sizes()->push_back(kFullParameterCount);
    }

    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const override {
        constexpr int kP = kFullParameterCount;
        const double* u = parameters[0];
        const std::array<double, kP> physical = toPhysical(u);
        ParameterVector p;
        std::copy(physical.begin(), physical.end(), p.begin());
        // Ceres evaluates a trial point without the Jacobian, then (when it is accepted) again with
        // it: the linearisation of the trial is kept for that second call.
        if (!std::equal(u, u + kP, cached_u_.begin()) || !cached_ok_) {
            std::copy(u, u + kP, cached_u_.begin());
            cached_ok_ = projection_.linearise(p, cached_);
        }
        if (!cached_ok_) return false;
        const Linearised& l = cached_;
        const int m = static_cast<int>(l.rows.size());
        for (int r = 0; r < m; ++r) residuals[r] = l.rows[r].dot(l.alpha) - l.y[r];
        const Priors& priors = projection_.objective_.priors;
        for (std::size_t t = 0; t < nonlinear_priors_.size(); ++t) {
            const int k = nonlinear_priors_[t];
            residuals[m + t] = (p[k] - priors[k]->mean) / priors[k]->std;
        }
        if (!jacobians || !jacobians[0]) return true;
        double* jac = jacobians[0];
        std::fill(jac, jac + num_residuals() * kP, 0.0);
        // ∂F/∂(a₀, a₁, n, ln K) at the projected α, weighted: one Jet evaluation per sample.
        using J = ceres::Jet<double, 4>;
        const ObservationModel& model = *projection_.objective_.model;
        const contact::ContactParameters<J> cp{J(projection_.wheel_.radius_m),
                                               J(projection_.wheel_.width_m),
                                               J(u[kN], 2),
                                               J(model.setup().sinkage_exponent_slip),
                                               J(l.alpha(0) * kModulusUnit),
                                               J(l.alpha(1) * kCohesionUnit),
                                               J(std::atan2(l.alpha(2), l.alpha(0))),
                                               exp(J(u[kK], 3)),
                                               J(0.0),
                                               J(u[kA0], 0),
                                               J(u[kA1], 1),
                                               p[kJmax],
                                               projection_.wheel_.lugShearOffset()};
        // With j_max free, its column ∂F/∂ln j_max (at the projected α) is a forward difference
        // from the Jet's value (the contact model takes j_max as a plain double): one double
        // evaluation per sample, not the two of a central difference. Its error, ~1e-5 of the
        // column (the step's first-order term and the quadrature's ~5e-11 of F over the step),
        // only shapes the steps: the polish and the covariance take the central difference of
        // observation_model.h.
        const int columns = shear_limit_ ? 5 : 4;
        Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m, columns);
        contact::ContactParameters<double> up{};
        constexpr double kStep = 1e-5;
        if (shear_limit_) {
            up = {projection_.wheel_.radius_m,
                  projection_.wheel_.width_m,
                  u[kN],
                  model.setup().sinkage_exponent_slip,
                  l.alpha(0) * kModulusUnit,
                  l.alpha(1) * kCohesionUnit,
                  std::atan2(l.alpha(2), l.alpha(0)),
                  std::exp(u[kK]),
                  0.0,
                  u[kA0],
                  u[kA1],
                  p[kJmax] * std::exp(kStep),
                  projection_.wheel_.lugShearOffset()};
        }
        projection_.forSamples([&](std::size_t t) {
            const std::size_t i = projection_.samples_[t];
            const Sample& s = model.sample(i);
            const contact::OperatingPoint<J> op{J(s.slip), J(s.slip_angle_rad.value_or(0.0)),
                                                J(s.entry_angle_rad), J(0.0), std::nullopt};
            const contact::WheelForces<J> f = modelForces(cp, op, model.setup());
            const J* channel[3] = {&f.fx, &f.fz, &f.my};
            std::array<double, 3> limit{};
            if (shear_limit_) {
                const contact::OperatingPoint<double> od{s.slip, s.slip_angle_rad.value_or(0.0),
                                                         s.entry_angle_rad, 0.0, std::nullopt};
                const contact::WheelForces<double> a = modelForces(up, od, model.setup());
                limit = {(a.fx - f.fx.a) / kStep, (a.fz - f.fz.a) / kStep, (a.my - f.my.a) / kStep};
            }
            const auto active = model.channels(i);
            auto row = static_cast<Eigen::Index>(projection_.first_row_[t]);
            for (int c = 0; c < 3; ++c) {
                if (!active[c]) continue;
                const double w = 1.0 / projection_.objective_.sigma[c];
                for (int k = 0; k < 4; ++k) d(row, k) = channel[c]->v[k] * w;
                if (shear_limit_) d(row, 4) = limit[c] * w;
                ++row;
            }
        });
        // Kaufman: J = P⊥ D, P⊥ the projector onto the complement of Φ N, N a basis of the
        // directions α can still move in on its face.
        Eigen::MatrixXd phi(m, 3);
        for (int r = 0; r < m; ++r) phi.row(r) = l.rows[r];
        Eigen::MatrixXd basis = Eigen::Matrix3d::Identity();
        if (!l.face.empty()) {
            Eigen::MatrixXd c(static_cast<int>(l.face.size()), 3);
            for (std::size_t r = 0; r < l.face.size(); ++r) c.row(static_cast<int>(r)) = l.face[r];
            basis = Eigen::FullPivLU<Eigen::MatrixXd>(c).kernel();
            if (basis.cols() == 1 && basis.norm() == 0.0) basis.resize(3, 0);
        }
        if (basis.cols() > 0) {
            const Eigen::MatrixXd columns = phi * basis;
            const Eigen::HouseholderQR<Eigen::MatrixXd> qr(columns);
            const Eigen::MatrixXd q =
                qr.householderQ() * Eigen::MatrixXd::Identity(m, columns.cols());
            d -= q * (q.transpose() * d);
        }
        static constexpr int kColumn[5] = {kA0, kA1, kN, kK, kJmax};
        for (int r = 0; r < m; ++r) {
            for (int k = 0; k < columns; ++k) jac[r * kP + kColumn[k]] = d(r, k);
        }
        const ParameterVector slope = physicalPerSolver(p);
        for (std::size_t t = 0; t < nonlinear_priors_.size(); ++t) {
            const int k = nonlinear_priors_[t];
            jac[(m + t) * kP + k] = slope[k] / priors[k]->std;
        }
        return true;
    }

private:
    const LinearProjection& projection_;
    mutable std::array<double, kFullParameterCount> cached_u_{};
    mutable Linearised cached_;
    mutable bool cached_ok_ = false;
    int alpha_priors_ = 0;
    std::vector<int> nonlinear_priors_;
    bool shear_limit_ = false;  // j_max free: a fifth column
};

ceres::CostFunction* LinearProjection::costFunction() const { return new Cost(*this); }

std::vector<ParameterVector> haltonDesign(int count,
                                          const std::array<bool, kFullParameterCount>& vary,
                                          const DesignBox& box, const ParameterVector& base,
                                          std::uint64_t seed) {
    static constexpr unsigned kPrimes[kFullParameterCount] = {2, 3, 5, 7, 11, 13, 17, 19};
    boost::random::mt19937_64 engine(seed);
    boost::random::uniform_real_distribution<double> uniform(0.0, 1.0);
    ParameterVector shift{};
    for (double& v : shift) v = uniform(engine);
    const ParameterVector lo = toSolver(box.lower), hi = toSolver(box.upper);
    std::vector<ParameterVector> points;
    for (int i = 0; i < count; ++i) {
        ParameterVector u = toSolver(base);
        int dimension = 0;
        for (int k = 0; k < kFullParameterCount; ++k) {
            if (!vary[k]) continue;
            double h =
                radicalInverse(static_cast<unsigned>(i + 1), kPrimes[dimension++]) + shift[k];
            h -= std::floor(h);
            u[k] = lo[k] + h * (hi[k] - lo[k]);
        }
        const auto p = toPhysical(u.data());
        ParameterVector point;
        std::copy(p.begin(), p.end(), point.begin());
        points.push_back(point);
    }
    return points;
}

}  // namespace terra::identification::detail
