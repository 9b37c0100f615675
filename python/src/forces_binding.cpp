#include "python/src/forces_binding.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/common/units.h"
#include "core/gsa/batch.h"
#include "core/io/json_reader.h"
#include "python/src/convert.h"
#include "python/src/interruptible.h"

namespace terra::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A flat input array: `count` values or one.
std::optional<Array> inputArray(py::handle object, const char* name, std::size_t count) {
    if (object.is_none()) return std::nullopt;
    Array a = alignedArray<double>(object);
    if (!a) throw std::invalid_argument(std::string(name) + ": expected numbers");
    if (a.ndim() != 1 || (static_cast<std::size_t>(a.size()) != count && a.size() != 1)) {
        throw std::invalid_argument(std::string(name) + ": expected a flat array of " +
                                    std::to_string(count) + " values or 1");
    }
    return a;
}

std::span<const double> view(const std::optional<Array>& a) {
    if (!a) return {};
    return {a->data(), static_cast<std::size_t>(a->size())};
}

// Degrees as given → radians as the command line converts them (units::degToRad).
std::vector<double> radians(std::span<const double> degrees) {
    std::vector<double> out(degrees.size());
    for (std::size_t i = 0; i < degrees.size(); ++i) out[i] = units::degToRad(degrees[i]);
    return out;
}

// The keyword options of forces() (the CLI's model flags): read as a run script's keys.
gsa::ModelOptions readOptions(const py::dict& options) {
    const nlohmann::json json = toJson(options);
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues);
    analysis::ModelChoices choices;
    analysis::readModelChoices(r, choices);
    bool quadratic = false;
    r.choice<bool>("model", quadratic, {{"full", false}, {"quadratic", true}});
    r.finish();
    if (!issues.empty()) raiseIssues(issues);
    gsa::ModelOptions out;
    out.exit = choices.exit;
    out.max_stress_angle_rad = choices.max_stress_angle_rad;
    out.bulldozing = choices.bulldozing;
    out.model = quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    return out;
}

py::dict forces(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                std::size_t count, py::handle slip, py::handle slip_angle_deg, py::handle load_n,
                py::handle entry_angle_deg, const py::dict& overrides, const py::dict& options,
                int threads, const std::string& invalid_soil, const py::object& progress) {
    if (invalid_soil != "raise" && invalid_soil != "flag") {
        throw std::invalid_argument("invalid_soil: \"" + invalid_soil +
                                    "\" is not one of raise, flag");
    }
    const gsa::ModelOptions model = readOptions(options);
    const std::optional<Array> s = inputArray(slip, "slip", count);
    const std::optional<Array> beta = inputArray(slip_angle_deg, "slip_angle_deg", count);
    const std::optional<Array> w = inputArray(load_n, "load_N", count);
    const std::optional<Array> theta = inputArray(entry_angle_deg, "entry_angle_deg", count);
    std::vector<std::string> keys;
    std::vector<Array> values;
    for (auto [key, value] : overrides) {
        keys.push_back(key.cast<std::string>());
        std::optional<Array> a = inputArray(value, keys.back().c_str(), count);
        if (!a) throw std::invalid_argument(keys.back() + ": expected numbers, got None");
        values.push_back(std::move(*a));
    }

    const auto n = static_cast<py::ssize_t>(count);
    py::dict out;
    std::vector<py::array_t<double>> arrays;
    const char* names[] = {"Fx_N",     "Fy_N", "Fz_N", "Mx_Nm",           "My_Nm",
                           "Mz_Nm",    "Fb_N", "Fs_N", "entry_angle_deg", "exit_angle_deg",
                           "sinkage_m"};
    for (const char* name : names) {
        arrays.emplace_back(n);
        out[name] = arrays.back();
    }
    py::array_t<std::uint8_t> status(n);
    auto span = [&](std::size_t i) { return std::span<double>(arrays[i].mutable_data(), count); };
    gsa::BatchOutputView view_out{span(0), span(1), span(2), span(3), span(4),  span(5),
                                  span(6), span(7), span(8), span(9), span(10), {}};
    view_out.status = {reinterpret_cast<gsa::SampleStatus*>(status.mutable_data()), count};
    std::vector<double*> pointers;  // taken with the GIL held
    for (py::array_t<double>& a : arrays) pointers.push_back(a.mutable_data());
    runInterruptible(
        [&](const WorkControl& work) {
            const std::vector<double> beta_rad = radians(view(beta));
            const std::vector<double> theta_rad = radians(view(theta));
            gsa::BatchInput input;
            input.count = count;
            input.slip = view(s);
            input.slip_angle_rad = beta_rad;
            input.load_n = view(w);
            input.entry_angle_rad = theta_rad;
            for (std::size_t k = 0; k < keys.size(); ++k) {
                input.soil.push_back(
                    {keys[k], {values[k].data(), static_cast<std::size_t>(values[k].size())}});
            }
            gsa::RunControl control;
            control.threads = threads;
            control.cancel = work.cancel;
            control.progress = work.progress;
            gsa::evaluateBatch(
                soil, wheel, input, model, view_out, control,
                invalid_soil == "raise" ? gsa::InvalidSoil::kThrow : gsa::InvalidSoil::kFlag);
            // Angles in degrees, and NaN where there is no result (the batch writes 0 there).
            constexpr double nan = std::numeric_limits<double>::quiet_NaN();
            for (std::size_t i = 0; i < count; ++i) {
                view_out.entry_angle_rad[i] = units::radToDeg(view_out.entry_angle_rad[i]);
                view_out.exit_angle_rad[i] = units::radToDeg(view_out.exit_angle_rad[i]);
                if (view_out.status[i] == gsa::SampleStatus::kOk) continue;
                for (double* a : pointers) a[i] = nan;
            }
            return true;
        },
        progress);
    out["status"] = status;
    return out;
}

}  // namespace

void bindForces(py::module_& m) {
    m.def("_forces", &forces, py::arg("soil"), py::arg("wheel"), py::arg("count"), py::arg("slip"),
          py::arg("slip_angle_deg"), py::arg("load_N"), py::arg("entry_angle_deg"),
          py::arg("overrides"), py::arg("options"), py::arg("threads"), py::arg("invalid_soil"),
          py::arg("progress") = py::none());
    py::list names;
    for (int code = 0; code <= static_cast<int>(gsa::SampleStatus::kNotEvaluated); ++code)
        names.append(gsa::statusName(static_cast<gsa::SampleStatus>(code)));
    m.attr("STATUS") = py::tuple(names);
}

}  // namespace terra::python
