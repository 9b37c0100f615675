// The box solver's active set at a kink of the cost on a bound (box_solver.h): a parameter there
// whose gradient pulls it inside, though every step inside raises the cost, is held without a
// pass of rejected steps. The cost is written out by hand, so the kink is known exactly.
#include "core/identification/box_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace terra::identification::detail {
namespace {

// Residuals (x₀ − 1 + 0.5 x₁, 1 + 2|x₁|): on x₁ ≥ 0 the second grows with x₁, but its derivative
// is reported from the side x₁ < 0 (−2 at x₁ = 0, as a model evaluated at a kink reports one
// side's): with x₁ ≥ 0 the minimum is (1, 0), where the gradient, −2 in x₁, says "inside".
class KinkCost final : public ceres::SizedCostFunction<2, 2> {
public:
    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const override {
        const double x0 = parameters[0][0], x1 = parameters[0][1];
        residuals[0] = x0 - 1.0 + 0.5 * x1;
        residuals[1] = 1.0 + 2.0 * std::abs(x1);
        if (jacobians && jacobians[0]) {
            jacobians[0][0] = 1.0;
            jacobians[0][1] = 0.5;
            jacobians[0][2] = 0.0;
            jacobians[0][3] = x1 > 0.0 ? 2.0 : -2.0;
        }
        return true;
    }
};

TEST(BoxSolver, AParameterAtAKinkOfItsBoundIsHeldWithoutRejectedSteps) {
    KinkCost cost;
    BoxProblem problem;
    problem.costs = {&cost};
    problem.losses = {nullptr};
    problem.lower = {-10.0, 0.0};
    problem.upper = {10.0, 10.0};
    problem.fixed = {false, false};
    // The kink, independently of the solver: the gradient at (1, 0) pulls x₁ inside (< 0),
    // yet the cost is higher at x₁ = 1e-4.
    double at_kink = 0.0, inside = 0.0;
    std::vector<double> gradient;
    ASSERT_TRUE(evaluateCost(problem, {1.0, 0.0}, at_kink, &gradient));
    EXPECT_LT(gradient[1], 0.0);
    ASSERT_TRUE(evaluateCost(problem, {1.0, 1e-4}, inside));
    EXPECT_GT(inside, at_kink);

    // From the bound, as a refinement's noise round starts from the last round's minimum.
    std::vector<double> x = {3.0, 0.0};
    BoxOptions options;
    options.gradient = true;
    options.bound_shortcuts = true;  // as in the global search, which tests a start on a bound
    const BoxSummary s = solveInBox(problem, x, options);
    ASSERT_TRUE(s.usable);
    EXPECT_TRUE(s.converged) << s.termination;
    EXPECT_EQ(x[1], 0.0);
    EXPECT_NEAR(x[0], 1.0, 1e-6);
    EXPECT_TRUE(s.at_bound[1]);
    EXPECT_NE(s.termination.find("gradient points inside"), std::string::npos) << s.termination;
    // x₀ alone, a linear problem: two steps. Released at the kink, x₁ cost a pass of rejected
    // steps that shrink the trust region until the function tolerance ends it (14 iterations in two
    // passes, checked with the kink test off).
    EXPECT_LE(s.iterations, 3);
}

}  // namespace
}  // namespace terra::identification::detail
