#include "core/gsa/saltelli_design.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace terra::gsa {
namespace {

std::size_t checkedSequenceDimension(const ParameterSpace& space) {
    if (space.dimension() == 0) throw std::invalid_argument("parameters: no parameter to vary");
    return 2 * space.dimension();
}

}  // namespace

SaltelliDesign::SaltelliDesign(ParameterSpace space, std::size_t base_samples, std::uint64_t seed)
    : space_(std::move(space)),
      base_samples_(base_samples),
      seed_(seed),
      sequence_(checkedSequenceDimension(space_), seed) {
    if (base_samples < 2) {
        throw std::invalid_argument("samples = " + std::to_string(base_samples) +
                                    " is outside the allowed range [2, inf)");
    }
}

Eigen::MatrixXd SaltelliDesign::rows(std::size_t begin, std::size_t end) const {
    if (begin > end || end > rows()) {
        throw std::out_of_range("design rows [" + std::to_string(begin) + ", " +
                                std::to_string(end) + ") outside [0, " + std::to_string(rows()) +
                                ")");
    }
    const std::size_t d = parameters();
    Eigen::MatrixXd out(static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(d));
    if (begin == end) return out;
    const std::size_t first = row(begin).sample, last = row(end - 1).sample;
    const std::size_t samples = last - first + 1;
    std::vector<double> points(samples * 2 * d);
    sequence_.generate(first, samples, points);
    std::vector<double> u(d), x(d);
    for (std::size_t r = begin; r < end; ++r) {
        const SaltelliRow which = row(r);
        const double* a = &points[(which.sample - first) * 2 * d];
        const double* b = a + d;
        for (std::size_t i = 0; i < d; ++i) u[i] = which.kind == 1 ? b[i] : a[i];
        if (which.kind >= 2) u[which.kind - 2] = b[which.kind - 2];
        space_.transform(u, x);
        for (std::size_t i = 0; i < d; ++i) {
            out(static_cast<Eigen::Index>(r - begin), static_cast<Eigen::Index>(i)) = x[i];
        }
    }
    return out;
}

}  // namespace terra::gsa
