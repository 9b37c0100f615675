#include "python/src/inputs_binding.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "core/analysis/soil_posterior.h"
#include "core/identification/parameters.h"
#include "core/io/json_reader.h"
#include "python/src/convert.h"

namespace terra::python {
namespace {

using soil::SoilParameters;
using wheel::WheelParameters;

// A preset name or file, a dict (read as a soil or wheel file would be), or the object itself.
template <typename T, typename Resolve, typename FromJson>
T resolve(py::handle spec, const char* what, Resolve resolve_name, FromJson from_json) {
    if (py::isinstance<T>(spec)) return spec.cast<T>();
    Result<T> read = [&]() -> Result<T> {
        if (py::isinstance<py::str>(spec)) return resolve_name(spec.cast<std::string>());
        if (py::isinstance<py::dict>(spec)) return from_json(toJson(spec), what);
        if (PyObject_HasAttrString(spec.ptr(), "__fspath__")) {
            return resolve_name(py::str(spec.attr("__fspath__")()).cast<std::string>());
        }
        return std::vector<Issue>{
            {what, "expected a preset name, a JSON file or a dict, got " +
                       py::str(py::type::of(spec).attr("__name__")).cast<std::string>()}};
    }();
    if (!read) raiseIssues(read.issues());
    return read.value();
}

SoilParameters makeSoil(py::handle spec) {
    return resolve<SoilParameters>(
        spec, "soil",
        [](const std::string& name) { return io::resolveSoil(presetLocations(), name); },
        [](const nlohmann::json& j, const char* where) { return io::soilFromJson(j, where); });
}

WheelParameters makeWheel(py::handle spec) {
    return resolve<WheelParameters>(
        spec, "wheel",
        [](const std::string& name) { return io::resolveWheel(presetLocations(), name); },
        [](const nlohmann::json& j, const char* where) { return io::wheelFromJson(j, where); });
}

// Fields in file units over a soil, each checked as a soil file's key would be (unknown keys
// named with the nearest field, values against their ranges, and the soil's cross-field rule).
SoilParameters withOverrides(SoilParameters soil, const py::kwargs& overrides) {
    if (overrides.empty()) return soil;
    nlohmann::json json = io::toJson(soil);
    for (auto [key, value] : overrides) json[key.cast<std::string>()] = toJson(value);
    Result<SoilParameters> read = io::soilFromJson(json, "soil");
    if (!read) raiseIssues(read.issues());
    return read.value();
}

const soil::SoilField& soilField(const std::string& key) {
    const soil::SoilField* field = soil::findSoilField(key);
    if (field) return *field;
    std::vector<std::string> keys;
    for (const soil::SoilField& f : soil::soilFields()) keys.emplace_back(f.key);
    const std::string near = nearestName(key, keys);
    throw py::key_error(key + " is not a soil field" +
                        (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
}

// The exact doubles (SI), so that a soil sent to a Dask worker is bit for bit the same.
py::tuple soilState(const SoilParameters& s) {
    py::list values;
    for (const soil::SoilField& f : soil::soilFields()) values.append(s.*f.member);
    return py::make_tuple(s.name, s.source, values);
}

SoilParameters soilFromState(const py::tuple& state) {
    SoilParameters s;
    s.name = state[0].cast<std::string>();
    s.source = state[1].cast<std::string>();
    const auto values = state[2].cast<std::vector<double>>();
    const auto fields = soil::soilFields();
    if (values.size() != fields.size()) throw std::invalid_argument("soil state: wrong size");
    for (std::size_t i = 0; i < fields.size(); ++i) s.*fields[i].member = values[i];
    return s;
}

}  // namespace

void bindInputs(py::module_& m) {
    py::class_<SoilParameters>(m, "Soil", R"doc(
A homogeneous deformable soil (Bekker pressure-sinkage, Janosi-Hanamoto shear; docs/soils.md).

Made by terrastudio.soil(). Fields are read by their soil-file keys in the file units
(soil["phi_deg"] -> 29.0); to_dict() gives the soil file's JSON object.
)doc")
        .def_readonly("name", &SoilParameters::name, "Human-readable name.")
        .def_readonly("source", &SoilParameters::source, "Where the values come from.")
        .def(
            "__getitem__",
            [](const SoilParameters& s, const std::string& key) {
                return soil::userValue(s, soilField(key));
            },
            py::arg("key"), "A field in its file unit, by its file key (\"phi_deg\").")
        .def(
            "keys",
            [](const SoilParameters&) {
                std::vector<std::string> keys;
                for (const soil::SoilField& f : soil::soilFields()) keys.emplace_back(f.key);
                return keys;
            },
            "The soil-file keys of the fields, in file order.")
        .def(
            "to_dict", [](const SoilParameters& s) { return fromJson(io::toJson(s)); },
            "The soil file's JSON object (file units).")
        .def("__repr__",
             [](const SoilParameters& s) {
                 return "<terrastudio.Soil " + py::repr(py::str(s.name)).cast<std::string>() + ">";
             })
        .def("__eq__",
             [](const SoilParameters& a, const SoilParameters& b) {
                 for (const soil::SoilField& f : soil::soilFields()) {
                     if (a.*f.member != b.*f.member) return false;
                 }
                 return a.name == b.name && a.source == b.source;
             })
        .def(py::pickle([](const SoilParameters& s) { return soilState(s); },
                        [](const py::tuple& state) { return soilFromState(state); }));

    py::class_<WheelParameters>(m, "Wheel", R"doc(
A rigid wheel: radius r_m and width b_m [m]. Made by terrastudio.wheel().
)doc")
        .def_readonly("name", &WheelParameters::name)
        .def_readonly("source", &WheelParameters::source)
        .def_readonly("r_m", &WheelParameters::radius_m, "Radius r [m].")
        .def_readonly("b_m", &WheelParameters::width_m, "Width b [m].")
        .def(
            "to_dict", [](const WheelParameters& w) { return fromJson(io::toJson(w)); },
            "The wheel file's JSON object.")
        .def("__repr__",
             [](const WheelParameters& w) {
                 return "<terrastudio.Wheel " + py::repr(py::str(w.name)).cast<std::string>() + ">";
             })
        .def("__eq__",
             [](const WheelParameters& a, const WheelParameters& b) {
                 return a.name == b.name && a.source == b.source && a.radius_m == b.radius_m &&
                        a.width_m == b.width_m && a.grouser_height_m == b.grouser_height_m &&
                        a.grouser_count == b.grouser_count &&
                        a.grouser_thickness_m == b.grouser_thickness_m &&
                        a.lug_effect_coefficient == b.lug_effect_coefficient;
             })
        // Every field, the grousers and λ_s included: the lug model (docs/model.md, "Lugs") reads
        // them, so a wheel sent to a worker process must keep them.
        .def(py::pickle(
            [](const WheelParameters& w) {
                return py::make_tuple(w.name, w.source, w.radius_m, w.width_m, w.grouser_height_m,
                                      w.grouser_count, w.grouser_thickness_m,
                                      w.lug_effect_coefficient);
            },
            [](const py::tuple& t) {
                WheelParameters w{t[0].cast<std::string>(), t[1].cast<std::string>(),
                                  t[2].cast<double>(), t[3].cast<double>()};
                if (t.size() >= 8) {
                    w.grouser_height_m = t[4].cast<double>();
                    w.grouser_count = t[5].cast<double>();
                    w.grouser_thickness_m = t[6].cast<double>();
                    w.lug_effect_coefficient = t[7].cast<double>();
                }
                return w;
            }));

    m.def(
        "soil",
        [](py::handle spec, const py::kwargs& overrides) {
            return withOverrides(makeSoil(spec), overrides);
        },
        py::arg("spec"), R"doc(
soil(spec, **fields) -> Soil

spec: a preset name ("sandy-loam", terrastudio.presets("soils")), a path to a soil JSON file,
a dict with a soil file's keys, or a Soil. Keyword fields (file keys and units, e.g.
phi_deg=30.0, c_kPa=2.0) replace the spec's values. Raises ValueError naming the field, the
value and its allowed range, as the command line does.
)doc");
    m.def(
        "wheel", [](py::handle spec) { return makeWheel(spec); }, py::arg("spec"), R"doc(
wheel(spec) -> Wheel

spec: a preset name ("A", "B"), a path to a wheel JSON file, a dict {"r_m", "b_m", ...} or a
Wheel. Raises ValueError as the command line does.
)doc");
    m.def(
        "presets",
        [](const std::string& kind) {
            if (kind != "soils" && kind != "wheels" && kind != "scenarios") {
                throw std::invalid_argument("presets: kind \"" + kind +
                                            "\" is not one of soils, wheels, scenarios");
            }
            return io::presetNames(presetLocations(), kind);
        },
        py::arg("kind") = "soils", "The preset names of one kind: soils, wheels or scenarios.");
    m.def(
        "soil_fields",
        []() {
            py::list out;
            for (const soil::SoilField& f : soil::soilFields()) {
                py::dict d;
                d["key"] = f.key, d["unit"] = f.unit, d["symbol"] = f.symbol;
                d["label"] = f.label, d["description"] = f.description;
                d["low"] = f.range.low, d["high"] = f.range.high;
                out.append(d);
            }
            return out;
        },
        "Every soil field: key, unit, symbol, label, description and allowed range (file units).");
    m.def(
        "identified_parameters",
        []() {
            // The core's one table of the identified parameters (issue 26): Python names them
            // from it, as the command line does.
            py::list out;
            for (const identification::ParameterField& f : identification::parameterFields()) {
                py::dict d;
                d["key"] = f.key, d["unit"] = f.unit, d["symbol"] = f.symbol;
                d["label"] = f.label, d["description"] = f.description;
                d["low"] = f.range.low, d["high"] = f.range.high, d["to_si"] = f.to_si;
                d["refined"] = identification::fullParameterOf(f).has_value();
                d["soil_key"] = analysis::soilKeyOf(f.key);
                const std::string old = identification::oldKeyOf(f);
                d["old_key"] = old == f.key ? py::object(py::none()) : py::str(old);
                out.append(d);
            }
            return out;
        },
        "Every identified parameter (the table `identify` reads and writes): key, unit, symbol, "
        "label, description, allowed range (its unit), to_si, refined (a parameter of the full "
        "model), soil_key (its soil file key) and old_key (its deprecated key, or None).");
    m.def(
        "_deprecation_note",
        [](const std::string& key) -> py::object {
            if (!identification::lookupParameter(key).deprecated) return py::none();
            return py::str(identification::deprecationNote(key));
        },
        py::arg("key"));
    m.def("_set_data_dir", &setDataDir);
}

}  // namespace terra::python
