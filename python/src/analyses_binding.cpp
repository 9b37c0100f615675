#include "python/src/analyses_binding.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <any>
#include <string>
#include <vector>

#include "core/analysis/identification.h"
#include "core/analysis/registry.h"
#include "core/analysis/rover.h"
#include "core/analysis/stresses.h"
#include "core/identification/data_set.h"
#include "core/io/json_reader.h"
#include "core/scenario/scenario_json.h"
#include "python/src/convert.h"
#include "python/src/interruptible.h"

namespace terra::python {
namespace {

const analysis::AnalysisType& typeNamed(const std::string& name) {
    if (const analysis::AnalysisType* type = analysis::findAnalysisType(name)) return *type;
    const std::vector<std::string> names = analysis::analysisTypeNames();
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    const std::string near = nearestName(name, names);
    throw std::invalid_argument("analysis \"" + name + "\" is not one of " + list +
                                (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
}

// A data set given as columns (the CSV columns of data_set.h), read by the CSV reader so that
// the same rows are refused with the same messages.
identification::DataSet dataFromColumns(const py::dict& columns, bool skip_bad_rows, bool refine) {
    std::vector<std::string> names;
    std::vector<std::vector<double>> values;
    for (auto [key, value] : columns) {
        names.push_back(key.cast<std::string>());
        values.push_back(alignedArray<double>(value).cast<std::vector<double>>());
        if (values.back().size() != values.front().size()) {
            throw std::invalid_argument(
                "data: column " + names.back() + " has " + std::to_string(values.back().size()) +
                " values, " + names.front() + " " + std::to_string(values.front().size()));
        }
    }
    std::string csv;
    for (std::size_t c = 0; c < names.size(); ++c) csv += (c ? "," : "") + names[c];
    csv += '\n';
    for (std::size_t r = 0; !values.empty() && r < values.front().size(); ++r) {
        for (std::size_t c = 0; c < names.size(); ++c)
            csv += (c ? "," : "") + formatNumber(values[c][r]);  // shortest round trip
        csv += '\n';
    }
    // The columns the identification's own CSV reader insists on (the full model reads data
    // without an entry angle and with any channels).
    auto read = identification::parseDataSet(
        csv, "data",
        skip_bad_rows ? identification::BadRows::kSkip : identification::BadRows::kStop,
        refine ? identification::ColumnNeeds::kFullModel : identification::ColumnNeeds::kDecoupled);
    if (!read) raiseIssues(read.issues());
    if (read->data.samples.empty()) throw std::invalid_argument("data: no valid samples");
    return read->data;
}

// A field run's maps (docs/python.md, "Maps"): name → {"values": rows × cols array from the
// north row, NaN where no data; "x0_m", "y0_m": the south-west corner; "cell_m"; "epsg"}.
py::dict mapsToDict(const scenario::FieldMaps& maps) {
    py::dict out;
    for (const auto& [key, raster] : scenario::mapRasters(maps)) {
        py::array_t<double> values(
            {static_cast<py::ssize_t>(raster->rows), static_cast<py::ssize_t>(raster->cols)});
        std::copy(raster->values.begin(), raster->values.end(), values.mutable_data());
        py::dict map;
        map["values"] = values;
        map["x0_m"] = raster->x_min_m;
        map["y0_m"] = raster->y_min_m;
        map["cell_m"] = raster->cell_m;
        map["epsg"] = raster->epsg ? py::object(py::int_(*raster->epsg)) : py::object(py::none());
        out[py::str(key)] = map;
    }
    return out;
}

py::dict run(const std::string& type_name, const soil::SoilParameters& soil,
             const wheel::WheelParameters& wheel, const py::dict& conditions,
             const py::dict& settings, py::object data, const py::object& progress, int threads) {
    const analysis::AnalysisType& type = typeNamed(type_name);
    constexpr int kMaxThreads = identification::IdentifyOptions::kMaxThreads;
    if (threads < 0 || threads > kMaxThreads) {
        throw std::invalid_argument("threads: " + std::to_string(threads) +
                                    " is outside the allowed range [0, " +
                                    std::to_string(kMaxThreads) + "] (0: one per core)");
    }
    const nlohmann::json conditions_json = toJson(conditions);
    const nlohmann::json settings_json = toJson(settings);
    std::vector<Issue> issues;
    analysis::Inputs inputs{soil, wheel, {}};
    io::ObjectReader c(conditions_json, issues);
    analysis::readConditions(c, inputs.conditions);
    c.finish();
    if (type.uses_inputs && issues.empty()) issues = analysis::validate(inputs);
    io::ObjectReader r(settings_json, issues);
    const analysis::ReadContext context{&presetLocations(), {}};
    std::any typed = type.read(r, context);
    r.finish();
    if (!issues.empty()) raiseIssues(issues);
    if (!data.is_none()) {
        auto* identification = std::any_cast<analysis::IdentificationSettings>(&typed);
        if (!identification) throw std::invalid_argument(type_name + " takes no data");
        identification->data =
            dataFromColumns(data, identification->skip_bad_rows, identification->refine);
        identification->csv = "data";
    }
    const analysis::Outcome outcome = runInterruptible(
        [&](const WorkControl& work) {
            analysis::Control control{work.cancel, work.progress};
            control.threads = threads;
            return type.run(typed, inputs, control);
        },
        progress);
    py::dict out;
    out["status"] = analysis::statusName(outcome.status);
    out["message"] = outcome.message;
    py::dict tables;
    for (const analysis::NamedTable& t : outcome.tables)
        tables[py::str(t.name)] = tableToDict(t.table);
    out["tables"] = tables;
    out["notes"] = outcome.notes;
    py::dict documents;
    for (const auto& [suffix, json] : outcome.documents)
        documents[py::str(suffix)] = fromJson(json);
    out["documents"] = documents;
    // What the tables do not hold.
    if (const auto* stresses = std::any_cast<analysis::StressResult>(&outcome.result)) {
        out["entry_angle_deg"] = stresses->entry_angle_deg;
        out["max_stress_angle_deg"] = stresses->max_stress_angle_deg;
        if (!stresses->message.empty()) out["message"] = stresses->message;
    }
    if (const auto* rover = std::any_cast<analysis::RoverResult>(&outcome.result);
        rover != nullptr && rover->run.maps) {
        out["maps"] = mapsToDict(*rover->run.maps);
    }
    if (const auto* fit = std::any_cast<analysis::IdentificationResult>(&outcome.result)) {
        out["usable"] = fit->usable();
        out["fit_time_ms"] = fit->fit_time_ms;
        if (!fit->message.empty()) out["message"] = fit->message;
    }
    return out;
}

// The scenario under every controller: the comparison table of `simulate --compare --json`.
py::object compareControllers(const py::dict& settings, const py::object& progress) {
    const nlohmann::json settings_json = toJson(settings);
    std::vector<Issue> issues;
    io::ObjectReader r(settings_json, issues);
    analysis::RoverSettings rover;
    analysis::readRoverSettings(r, analysis::ReadContext{&presetLocations(), {}}, rover);
    r.finish();
    if (!issues.empty()) raiseIssues(issues);
    if (rover.controller) {
        throw std::invalid_argument(
            "controller: compare_controllers runs every controller; drop controller=");
    }
    const nlohmann::json table = runInterruptible(
        [&](const WorkControl& work) {
            return analysis::controllerComparison(
                analysis::compareControllers(rover, analysis::Control{work.cancel, work.progress}));
        },
        progress);
    return fromJson(table);
}

// The soils a mission study can vary, by the keys of the rover's "soils" override.
py::dict scenarioSoils(const std::string& name) {
    Result<scenario::Scenario> loaded = scenario::resolveScenario(presetLocations(), name);
    if (!loaded) raiseIssues(loaded.issues());
    py::dict out;
    for (auto& [key, soil] : analysis::overridableSoils(loaded.value())) out[py::str(key)] = soil;
    return out;
}

}  // namespace

void bindAnalyses(py::module_& m) {
    m.def("_scenario_soils", &scenarioSoils, py::arg("scenario"));
    m.def("_run", &run, py::arg("type"), py::arg("soil"), py::arg("wheel"), py::arg("conditions"),
          py::arg("settings"), py::arg("data") = py::none(), py::arg("progress") = py::none(),
          py::arg("threads") = 1);
    m.def("_compare_controllers", &compareControllers, py::arg("settings"),
          py::arg("progress") = py::none());
    m.def(
        "analyses",
        []() {
            py::dict out;
            for (const analysis::AnalysisType& type : analysis::analysisTypes())
                out[py::str(type.name)] = type.summary;
            return out;
        },
        "The analyses of the registry, name -> one-line summary (terrastudio.run runs any).");
}

}  // namespace terra::python
