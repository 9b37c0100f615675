#pragma once
/// @file parameter_space.h
/// The uncertain parameters of a study and their distributions: independent uniform or
/// (truncated) normal marginals, and multivariate normal groups given a mean and a covariance
/// (an identification posterior with its correlations). A point u of the unit cube (0, 1)^d is
/// mapped to parameter values by inverse CDFs and, for a correlated group, x = μ + L z with
/// Σ = L Lᵀ (Cholesky) and z_k = Φ⁻¹(u_k) (docs/sensitivity.md, "Distributions").

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace terra::gsa {

/// X ~ U(low, high), low < high, both finite.
struct Uniform {
    double low = 0.0;
    double high = 1.0;
};

/// X ~ N(mean, sd²) truncated to [low, high] (infinite bounds: no truncation), sd > 0.
struct Normal {
    double mean = 0.0;
    double sd = 1.0;
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
};

using Marginal = std::variant<Uniform, Normal>;

/// An ordered list of named parameters. Parameter names are free here; the wheel studies use soil
/// file keys ("phi_deg") with values in the file's units.
class ParameterSpace {
public:
    /// Adds an independent parameter. Throws std::invalid_argument naming the parameter for a
    /// duplicate name, low ≥ high, sd ≤ 0, non-finite values, or a truncation holding no mass.
    void add(const std::string& name, const Marginal& marginal);

    /// Adds a group X ~ N(mean, covariance) (covariance symmetric positive definite, sizes equal
    /// to names.size()). Its parameters keep the given order: in a Sobol' study the k-th one
    /// stands for the k-th independent factor z_k of the Cholesky decomposition, i.e. its own
    /// variation plus what it carries of the later ones, minus what the earlier ones explain
    /// (docs/sensitivity.md). Throws std::invalid_argument naming the problem.
    void addMultivariateNormal(const std::vector<std::string>& names, const Eigen::VectorXd& mean,
                               const Eigen::MatrixXd& covariance);

    std::size_t dimension() const { return names_.size(); }
    const std::vector<std::string>& names() const { return names_; }
    /// Index of a parameter by name, or dimension() when absent.
    std::size_t find(const std::string& name) const;

    /// The marginal of parameter i when it is independent, nullptr when it is in a correlated
    /// group.
    const Marginal* marginal(std::size_t i) const;
    /// True when every parameter is an independent uniform.
    bool allUniform() const;

    /// Maps u ∈ (0, 1)^d to parameter values x (both of size dimension()).
    void transform(std::span<const double> u, std::span<double> x) const;

private:
    struct Group {
        std::size_t first = 0;  // index of the group's first parameter
        Eigen::VectorXd mean;
        Eigen::MatrixXd cholesky;  // lower triangular L, Σ = L Lᵀ
    };
    // Per parameter: its marginal, or the group it belongs to.
    struct Entry {
        Marginal marginal;
        int group = -1;
        double cdf_low = 0.0, cdf_high = 1.0;  // Φ at a truncated normal's bounds
    };
    void addName(const std::string& name);

    std::vector<std::string> names_;
    std::vector<Entry> entries_;
    std::vector<Group> groups_;
};

}  // namespace terra::gsa
