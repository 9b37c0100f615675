#include "python/src/studies_binding.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/global_sensitivity.h"
#include "core/common/units.h"
#include "core/gsa/wheel_studies.h"
#include "core/io/json_reader.h"
#include "python/src/convert.h"
#include "python/src/interruptible.h"

namespace terra::python {
namespace {

using gsa::Output;

// What sobol() and morris() share, as the package passes it (plain Python values).
struct StudyArguments {
    soil::SoilParameters soil;
    wheel::WheelParameters wheel;
    py::dict parameters;    // key -> (low, high) | {"range": [..]} | {"normal": [m, sd], "bounds"}
    py::object correlated;  // None | {"keys", "mean", "covariance"}
    std::vector<double> slips;
    std::vector<double> slip_angles_deg;
    std::optional<double> load_n;
    std::optional<double> entry_angle_deg;
    std::vector<std::string> outputs;
    py::dict options;  // model choices, as forces()
};

std::vector<double> numbers(py::handle value, const std::string& what) {
    const auto a = alignedArray<double>(value);
    if (!a) {
        throw std::invalid_argument(what + ": expected numbers, got " +
                                    py::repr(value).cast<std::string>());
    }
    return {a.data(), a.data() + a.size()};
}

std::vector<double> pair(py::handle value, const std::string& what) {
    std::vector<double> v = numbers(value, what);
    if (v.size() != 2) throw std::invalid_argument(what + ": expected two numbers [low, high]");
    return v;
}

// One parameter's distribution: (low, high), {"range": [low, high]} or {"normal": [mean, sd]}
// with optional "bounds": [low, high] (the keys of a script's study definition).
gsa::Marginal marginalOf(const std::string& key, py::handle spec) {
    if (!py::isinstance<py::dict>(spec)) {
        const std::vector<double> range = pair(spec, "parameters." + key);
        return gsa::Uniform{range[0], range[1]};
    }
    const py::dict d = spec.cast<py::dict>();
    for (auto [name, value] : d) {
        const std::string n = name.cast<std::string>();
        if (n != "range" && n != "normal" && n != "bounds") {
            throw std::invalid_argument("parameters." + key + "." + n +
                                        ": unknown key (range, normal, bounds)");
        }
    }
    if (d.contains("range") == d.contains("normal")) {
        throw std::invalid_argument("parameters." + key + ": give \"range\" or \"normal\"");
    }
    if (d.contains("range")) {
        if (d.contains("bounds")) {
            throw std::invalid_argument("parameters." + key + ".bounds: only with \"normal\"");
        }
        const std::vector<double> range = pair(d["range"], "parameters." + key + ".range");
        return gsa::Uniform{range[0], range[1]};
    }
    const std::vector<double> normal = pair(d["normal"], "parameters." + key + ".normal");
    gsa::Normal out{normal[0], normal[1]};
    if (d.contains("bounds")) {
        const std::vector<double> bounds = pair(d["bounds"], "parameters." + key + ".bounds");
        out.low = bounds[0], out.high = bounds[1];
    }
    return out;
}

gsa::ParameterSpace spaceOf(const py::dict& parameters, const py::object& correlated) {
    gsa::ParameterSpace space;
    for (auto [key, spec] : parameters) {
        const std::string k = key.cast<std::string>();
        space.add(k, marginalOf(k, spec));
    }
    if (!correlated.is_none()) {
        const py::dict c = correlated.cast<py::dict>();
        for (const char* required : {"keys", "mean", "covariance"}) {
            if (!c.contains(required)) {
                throw std::invalid_argument(std::string("correlated.") + required + ": missing");
            }
        }
        const auto keys = c["keys"].cast<std::vector<std::string>>();
        const std::vector<double> mean = numbers(c["mean"], "correlated.mean");
        const std::vector<double> flat = numbers(c["covariance"], "correlated.covariance");
        const std::size_t n = keys.size();
        if (mean.size() != n || flat.size() != n * n) {
            throw std::invalid_argument(
                "correlated: " + std::to_string(n) + " keys need a mean of " + std::to_string(n) +
                " values and a " + std::to_string(n) + "×" + std::to_string(n) + " covariance");
        }
        Eigen::MatrixXd covariance(n, n);
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = 0; j < n; ++j) covariance(i, j) = flat[i * n + j];
        }
        space.addMultivariateNormal(keys, Eigen::Map<const Eigen::VectorXd>(mean.data(), n),
                                    covariance);
    }
    if (space.dimension() == 0) {
        throw std::invalid_argument("parameters: no uncertain parameters");
    }
    return space;
}

gsa::ModelOptions modelOptions(const py::dict& options, contact::ContactModel* contact_model) {
    const nlohmann::json json = toJson(options);
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues);
    analysis::ModelChoices choices;
    analysis::readModelChoices(r, choices);
    bool quadratic = false;
    r.choice<bool>("model", quadratic, {{"full", false}, {"quadratic", true}});
    r.allow("compaction");  // read by studyOf
    r.finish();
    if (!issues.empty()) raiseIssues(issues);
    gsa::ModelOptions out;
    out.exit = choices.exit;
    out.max_stress_angle_rad = choices.max_stress_angle_rad;
    out.bulldozing = choices.bulldozing;
    out.model = quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    if (contact_model) *contact_model = out.model;
    return out;
}

gsa::WheelStudy studyOf(const StudyArguments& a) {
    gsa::WheelStudy study;
    study.soil = a.soil;
    study.wheel = a.wheel;
    study.model = modelOptions(a.options, nullptr);
    study.grid.slips = a.slips;
    study.grid.slip_angles_rad.clear();
    for (double beta : a.slip_angles_deg)
        study.grid.slip_angles_rad.push_back(units::degToRad(beta));
    if (a.load_n && a.entry_angle_deg) {
        throw std::invalid_argument("load_N: give either the load or the entry angle, not both");
    }
    study.grid.load_n = a.load_n;
    if (a.entry_angle_deg) study.grid.entry_angle_rad = units::degToRad(*a.entry_angle_deg);
    if (!a.load_n && !a.entry_angle_deg) {
        throw std::invalid_argument("load_N: give the load (θ_f solved) or the entry angle");
    }
    study.outputs.clear();
    for (const std::string& name : a.outputs) {
        const std::optional<Output> output = gsa::findOutput(name);
        if (!output) {
            std::string list;
            for (const std::string& n : gsa::outputNames()) list += (list.empty() ? "" : ", ") + n;
            const std::string near = nearestName(name, gsa::outputNames());
            throw std::invalid_argument("outputs: \"" + name + "\" is not one of " + list +
                                        (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
        }
        study.outputs.push_back(*output);
    }
    study.parameters = spaceOf(a.parameters, a.correlated);
    if (a.options.contains("compaction")) {
        // The compaction outputs' settings, as a script's study "compaction" object.
        const nlohmann::json json = toJson(a.options["compaction"].cast<py::dict>());
        std::vector<Issue> issues;
        io::ObjectReader r(json, issues, {}, "compaction");
        analysis::readCompactionStudy(r, study.compaction);
        r.finish();
        if (!issues.empty()) raiseIssues(issues);
    }
    return study;
}

// Eigen (column-major) to a C-order numpy array, and back.
template <typename Matrix>
py::array_t<typename Matrix::Scalar> toNumpy(const Matrix& m) {
    using T = typename Matrix::Scalar;
    py::array_t<T> out({m.rows(), m.cols()});
    auto a = out.template mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        for (Eigen::Index j = 0; j < m.cols(); ++j) a(i, j) = m(i, j);
    }
    return out;
}

template <typename Matrix>
Matrix fromNumpy(py::handle object, Eigen::Index cols) {
    using T = typename Matrix::Scalar;
    const auto a = alignedArray<T>(object);
    if (!a || a.ndim() != 2 || a.shape(1) != cols) {
        throw std::invalid_argument("chunk: expected a 2-D array with " + std::to_string(cols) +
                                    " columns");
    }
    Matrix m(a.shape(0), a.shape(1));
    auto v = a.template unchecked<2>();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        for (Eigen::Index j = 0; j < m.cols(); ++j) m(i, j) = v(i, j);
    }
    return m;
}

const char* statusName(gsa::StudyStatus status) {
    switch (status) {
        case gsa::StudyStatus::kCompleted:
            return "completed";
        case gsa::StudyStatus::kCancelled:
            return "cancelled";
        case gsa::StudyStatus::kTooManyFailures:
            return "too many failures";
    }
    return "?";
}

// Per output, the parameters × points block of a matrix, shaped [parameter, slip] (one slip
// angle given as a number) or [parameter, slip angle, slip].
py::dict perOutput(const Eigen::MatrixXd& m, const gsa::WheelStudy& study, bool angle_axis) {
    py::dict out;
    const std::size_t points = study.grid.size(), d = study.parameters.dimension();
    for (std::size_t o = 0; o < study.outputs.size(); ++o) {
        const Eigen::MatrixXd block =
            m.middleCols(static_cast<Eigen::Index>(o * points), static_cast<Eigen::Index>(points));
        py::array a = toNumpy(block);
        if (angle_axis) {
            a = a.reshape({static_cast<py::ssize_t>(d),
                           static_cast<py::ssize_t>(study.grid.slip_angles_rad.size()),
                           static_cast<py::ssize_t>(study.grid.slips.size())});
        }
        out[py::str(gsa::outputName(study.outputs[o]))] = a;
    }
    return out;
}

py::dict common(const gsa::WheelStudy& study, gsa::StudyStatus status, const std::string& message,
                std::size_t evaluations, const std::vector<std::size_t>& dropped,
                const std::vector<gsa::FailureCounts>& failures) {
    if (status == gsa::StudyStatus::kTooManyFailures) throw std::runtime_error(message);
    py::dict out;
    out["parameters"] = study.parameters.names();
    std::vector<std::string> outputs;
    for (Output o : study.outputs) outputs.emplace_back(gsa::outputName(o));
    out["outputs"] = outputs;
    out["slip"] = study.grid.slips;
    std::vector<double> angles;
    for (double b : study.grid.slip_angles_rad)
        angles.push_back(roundSignificant(units::radToDeg(b)));
    out["slip_angle_deg"] = angles;
    out["status"] = statusName(status);
    out["message"] = message;
    out["evaluations"] = evaluations;
    out["dropped"] = dropped;
    std::vector<std::size_t> failed;
    for (const gsa::FailureCounts& f : failures) failed.push_back(f.total());
    out["failed_evaluations"] = failed;
    return out;
}

py::dict sobolDict(const gsa::SobolStudyResult& r, const gsa::WheelStudy& study, bool angle_axis) {
    py::dict out = common(study, r.status, r.message, r.evaluations, r.dropped_samples, r.failures);
    out["S1"] = perOutput(r.indices.first_order, study, angle_axis);
    out["ST"] = perOutput(r.indices.total, study, angle_axis);
    out["S1_conf"] = perOutput(r.indices.first_order_conf, study, angle_axis);
    out["ST_conf"] = perOutput(r.indices.total_conf, study, angle_axis);
    out["samples"] = r.base_samples;
    return out;
}

py::dict morrisDict(const gsa::MorrisStudyResult& r, const gsa::WheelStudy& study,
                    bool angle_axis) {
    py::dict out =
        common(study, r.status, r.message, r.evaluations, r.dropped_trajectories, r.failures);
    out["mu_star"] = perOutput(r.indices.mu_star, study, angle_axis);
    out["mu"] = perOutput(r.indices.mu, study, angle_axis);
    out["sigma"] = perOutput(r.indices.sigma, study, angle_axis);
    out["mu_star_conf"] = perOutput(r.indices.mu_star_conf, study, angle_axis);
    return out;
}

// A study and its design; Design is gsa::SaltelliDesign or gsa::MorrisDesign.
template <typename Design, typename Options>
class Plan {
public:
    Plan(const StudyArguments& arguments, Options options, bool angle_axis,
         const std::function<Design(const gsa::ParameterSpace&)>& make_design)
        : target_(studyOf(arguments)),
          design_(make_design(target_.study().parameters)),
          options_(options),
          angle_axis_(angle_axis) {}

    std::size_t rows() const { return design_.rows(); }
    std::size_t rowsPerGroup() const {
        if constexpr (std::is_same_v<Design, gsa::SaltelliDesign>) {
            return design_.rowsPerSample();
        } else {
            return design_.rowsPerTrajectory();
        }
    }
    std::size_t evaluationsPerRow() const { return target_.points(); }

    // Rows [begin, end): values (rows × columns) and status (rows × points).
    py::tuple evaluate(std::size_t begin, std::size_t end, int threads) const {
        if (begin > end || end > rows()) {
            throw std::invalid_argument("rows [" + std::to_string(begin) + ", " +
                                        std::to_string(end) + ") outside [0, " +
                                        std::to_string(rows()) + ")");
        }
        gsa::TargetValues values;
        {
            py::gil_scoped_release release;
            gsa::RunControl control;
            control.threads = threads;
            values = target_.evaluate(design_.rows(begin, end), control);
        }
        return py::make_tuple(toNumpy(values.values), toNumpy(values.status));
    }

    // The result from every row's outputs, as chunks in row order.
    py::dict gather(const py::list& chunks, int threads) const {
        std::vector<gsa::TargetValues> parts;
        for (py::handle chunk : chunks) {
            const auto pair = chunk.cast<py::tuple>();
            gsa::TargetValues part;
            part.values = fromNumpy<Eigen::MatrixXd>(pair[0], target_.columns());
            part.status = fromNumpy<gsa::StatusMatrix>(pair[1], target_.points());
            parts.push_back(std::move(part));
        }
        Options options = options_;
        options.bootstrap.threads = threads;
        py::gil_scoped_release release;
        const gsa::TargetValues values = gsa::concatenate(parts);
        if constexpr (std::is_same_v<Design, gsa::SaltelliDesign>) {
            const auto r = gsa::sobolResult(target_, design_, values, options);
            py::gil_scoped_acquire acquire;
            return sobolDict(r, target_.study(), angle_axis_);
        } else {
            const auto r = gsa::morrisResult(target_, design_, values, options);
            py::gil_scoped_acquire acquire;
            return morrisDict(r, target_.study(), angle_axis_);
        }
    }

    // The whole study here, through the core's study function.
    py::dict run(int threads, const py::object& progress) const {
        const auto study = [&](const WorkControl& work) {
            gsa::RunControl control;
            control.threads = threads;
            control.cancel = work.cancel;
            control.progress = work.progress;
            if constexpr (std::is_same_v<Design, gsa::SaltelliDesign>) {
                return gsa::sobolStudy(target_.study(), options_, control);
            } else {
                return gsa::morrisStudy(target_.study(), options_, control);
            }
        };
        const auto r = runInterruptible(study, progress);
        if constexpr (std::is_same_v<Design, gsa::SaltelliDesign>) {
            return sobolDict(r, target_.study(), angle_axis_);
        } else {
            return morrisDict(r, target_.study(), angle_axis_);
        }
    }

private:
    gsa::WheelTarget target_;
    Design design_;
    Options options_;
    bool angle_axis_;
};

using SobolPlan = Plan<gsa::SaltelliDesign, gsa::SobolOptions>;
using MorrisPlan = Plan<gsa::MorrisDesign, gsa::MorrisOptions>;

StudyArguments arguments(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                         py::dict parameters, py::object correlated, std::vector<double> slips,
                         std::vector<double> slip_angles_deg, std::optional<double> load_n,
                         std::optional<double> entry_angle_deg, std::vector<std::string> outputs,
                         py::dict options) {
    return {soil,
            wheel,
            std::move(parameters),
            std::move(correlated),
            std::move(slips),
            std::move(slip_angles_deg),
            load_n,
            entry_angle_deg,
            std::move(outputs),
            std::move(options)};
}

gsa::BootstrapOptions bootstrap(int resamples, double confidence, std::uint64_t seed) {
    gsa::BootstrapOptions b;
    b.resamples = resamples;
    b.confidence_level = confidence;
    b.seed = seed;
    return b;
}

template <typename P>
void planMethods(py::class_<P>& c) {
    c.def_property_readonly("rows", &P::rows)
        .def_property_readonly("rows_per_group", &P::rowsPerGroup)
        .def_property_readonly("evaluations_per_row", &P::evaluationsPerRow)
        .def("evaluate", &P::evaluate, py::arg("begin"), py::arg("end"), py::arg("threads") = 0)
        .def("gather", &P::gather, py::arg("chunks"), py::arg("threads") = 0)
        .def("run", &P::run, py::arg("threads") = 0, py::arg("progress") = py::none());
}

}  // namespace

// Sobol' indices of any model the caller evaluates on the design's rows (rows × outputs).
py::dict sobolIndices(const py::dict& parameters, const py::object& correlated, std::size_t samples,
                      std::uint64_t seed, py::handle values, int resamples, double confidence,
                      int threads) {
    const gsa::SaltelliDesign design(spaceOf(parameters, correlated), samples, seed);
    auto a = alignedArray<double>(values);
    if (!a || (a.ndim() != 1 && a.ndim() != 2) ||
        static_cast<std::size_t>(a.shape(0)) != design.rows()) {
        throw std::invalid_argument(
            "values: expected " + std::to_string(design.rows()) +
            " rows (one per design row), got shape " +
            py::repr(py::getattr(values, "shape", py::none())).cast<std::string>());
    }
    const Eigen::Index cols = a.ndim() == 1 ? 1 : a.shape(1);
    Eigen::MatrixXd y(a.shape(0), cols);
    const double* data = a.data();
    for (Eigen::Index i = 0; i < y.rows(); ++i) {
        for (Eigen::Index j = 0; j < cols; ++j) y(i, j) = data[i * cols + j];
    }
    gsa::BootstrapOptions options = bootstrap(resamples, confidence, seed);
    options.threads = threads;
    gsa::SobolIndices r;
    {
        py::gil_scoped_release release;
        r = gsa::estimateSobol(design, y, gsa::Mask(), options);
    }
    py::dict out;
    out["parameters"] = design.space().names();
    out["S1"] = toNumpy(r.first_order);
    out["ST"] = toNumpy(r.total);
    out["S1_conf"] = toNumpy(r.first_order_conf);
    out["ST_conf"] = toNumpy(r.total_conf);
    return out;
}

void bindStudies(py::module_& m) {
    m.def(
        "sobol_design",
        [](const py::dict& parameters, std::size_t samples, std::uint64_t seed,
           const py::object& correlated) {
            const gsa::SaltelliDesign design(spaceOf(parameters, correlated), samples, seed);
            return toNumpy(design.rows(0, design.rows()));
        },
        py::arg("parameters"), py::arg("samples") = 4096, py::arg("seed") = 1,
        py::arg("correlated") = py::none(), R"doc(
sobol_design(parameters, samples=4096, seed=1, correlated=None) -> array [rows, parameter]

Saltelli's design (docs/sensitivity.md) over any parameters (names free, distributions as in
sobol()): samples (d + 2) rows in the order A_0, B_0, AB_1,0 ... AB_d,0, A_1, ... Evaluate any
model on them and pass the outputs to sobol_indices().
)doc");
    m.def("sobol_indices", &sobolIndices, py::arg("parameters"), py::arg("correlated"),
          py::arg("samples"), py::arg("seed"), py::arg("values"), py::arg("resamples") = 1000,
          py::arg("confidence") = 0.95, py::arg("threads") = 0);

    py::class_<SobolPlan> sobol(m, "_SobolPlan");
    sobol.def(
        py::init([](const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                    py::dict parameters, py::object correlated, std::vector<double> slips,
                    std::vector<double> slip_angles_deg, std::optional<double> load_n,
                    std::optional<double> entry_angle_deg, std::vector<std::string> outputs,
                    py::dict options, bool angle_axis, std::size_t samples, std::uint64_t seed,
                    int resamples, double confidence, double max_failed_fraction) {
            gsa::SobolOptions o;
            o.base_samples = samples;
            o.seed = seed;
            o.bootstrap = bootstrap(resamples, confidence, seed);
            o.max_failed_fraction = max_failed_fraction;
            gsa::requireValid(o);
            const StudyArguments a =
                arguments(soil, wheel, parameters, correlated, slips, slip_angles_deg, load_n,
                          entry_angle_deg, outputs, options);
            return std::make_unique<SobolPlan>(a, o, angle_axis,
                                               [&](const gsa::ParameterSpace& space) {
                                                   return gsa::SaltelliDesign(space, samples, seed);
                                               });
        }),
        py::arg("soil"), py::arg("wheel"), py::arg("parameters"), py::arg("correlated"),
        py::arg("slips"), py::arg("slip_angles_deg"), py::arg("load_N"), py::arg("entry_angle_deg"),
        py::arg("outputs"), py::arg("options"), py::arg("angle_axis"), py::arg("samples"),
        py::arg("seed"), py::arg("resamples"), py::arg("confidence"),
        py::arg("max_failed_fraction"));
    planMethods(sobol);

    py::class_<MorrisPlan> morris(m, "_MorrisPlan");
    morris.def(py::init([](const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                           py::dict parameters, std::vector<double> slips,
                           std::vector<double> slip_angles_deg, std::optional<double> load_n,
                           std::optional<double> entry_angle_deg, std::vector<std::string> outputs,
                           py::dict options, bool angle_axis, std::size_t trajectories, int levels,
                           std::uint64_t seed, int resamples, double confidence,
                           double max_failed_fraction) {
                   gsa::MorrisOptions o;
                   o.trajectories = trajectories;
                   o.levels = levels;
                   o.seed = seed;
                   o.bootstrap = bootstrap(resamples, confidence, seed);
                   o.max_failed_fraction = max_failed_fraction;
                   gsa::requireValid(o);
                   const StudyArguments a =
                       arguments(soil, wheel, parameters, py::none(), slips, slip_angles_deg,
                                 load_n, entry_angle_deg, outputs, options);
                   return std::make_unique<MorrisPlan>(
                       a, o, angle_axis, [&](const gsa::ParameterSpace& space) {
                           return gsa::MorrisDesign(space, trajectories, levels, seed);
                       });
               }),
               py::arg("soil"), py::arg("wheel"), py::arg("parameters"), py::arg("slips"),
               py::arg("slip_angles_deg"), py::arg("load_N"), py::arg("entry_angle_deg"),
               py::arg("outputs"), py::arg("options"), py::arg("angle_axis"),
               py::arg("trajectories"), py::arg("levels"), py::arg("seed"), py::arg("resamples"),
               py::arg("confidence"), py::arg("max_failed_fraction"));
    planMethods(morris);
}

}  // namespace terra::python
