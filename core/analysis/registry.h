#pragma once
/// @file registry.h
/// The analysis types the product offers, by name: what `terrastudio run` dispatches on (no
/// hand-written if/else), what the studio draws figures for and what the Python module lists and
/// runs (terrastudio.analyses(), terrastudio.run()). A new analysis is one service (settings,
/// reader, compute, outcome; docs/architecture.md) and one line in registry.cpp; the services'
/// headers only forward-declare AnalysisType (the registry includes them, not the reverse).

#include <any>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"

namespace terra::analysis {

/// Where the settings of a script's analysis are read: presets, and the directory relative
/// files (data sets, scenarios) are found in.
struct ReadContext {
    const io::PresetLocations* locations = nullptr;
    std::filesystem::path base_dir;

    /// A preset name ("sandy-loam") as it is; a relative JSON file ("soils/wet.json") against
    /// base_dir, the script's directory, so that the io::resolve* functions find it.
    std::string presetOrFile(std::string name) const {
        if (name.ends_with(".json") && std::filesystem::path(name).is_relative() &&
            !base_dir.empty())
            name = (base_dir / name).string();
        return name;
    }
};

/// One figure an analysis type offers: its key (a script's "plots") and the image it is written
/// to (NAME + suffix + ".png").
struct FigureSpec {
    std::string key;
    std::string file_suffix;
};

/// An analysis type: its name, its tables and figures, and its settings reader and runner.
struct AnalysisType {
    std::string name;                 ///< "forces"
    std::string summary;              ///< one line for the docs and --help
    std::vector<std::string> tables;  ///< names of its tables (expectations' "table"), main first
    std::vector<FigureSpec> figures;  ///< every figure, in the default order
    /// false: the analysis brings its own soil and robot (rover: the scenario's), so a script's
    /// soil, set, wheel and conditions do not apply to it.
    bool uses_inputs = true;
    /// Reads the type's own keys of one analysis object (its settings), reporting every problem
    /// through the reader; the result is the settings, type-erased.
    std::function<std::any(io::ObjectReader&, const ReadContext&)> read;
    /// Computes it: settings from `read`, inputs checked (validate(Inputs)).
    std::function<Outcome(const std::any& settings, const Inputs&, const Control&)> run;
};

/// Every analysis type, in the order of the docs.
const std::vector<AnalysisType>& analysisTypes();
/// The type of that name, or nullptr.
const AnalysisType* findAnalysisType(std::string_view name);
/// Their names ("forces", "soil-curves", …).
std::vector<std::string> analysisTypeNames();

/// Builds an AnalysisType from a service's typed functions: `read(reader, context, settings)`
/// fills a Settings, `compute(inputs, settings, control)` returns a Result, and
/// `outcome(result)` gives its tables.
template <typename Settings, typename Read, typename Compute, typename ToOutcome>
AnalysisType makeAnalysisType(std::string name, std::string summary,
                              std::vector<std::string> tables, std::vector<FigureSpec> figures,
                              Read read, Compute compute, ToOutcome outcome,
                              bool uses_inputs = true) {
    AnalysisType type;
    type.name = std::move(name);
    type.summary = std::move(summary);
    type.tables = std::move(tables);
    type.figures = std::move(figures);
    type.uses_inputs = uses_inputs;
    type.read = [read](io::ObjectReader& r, const ReadContext& context) -> std::any {
        Settings settings;
        read(r, context, settings);
        return settings;
    };
    type.run = [compute, outcome](const std::any& settings, const Inputs& inputs,
                                  const Control& control) {
        return outcome(compute(inputs, std::any_cast<const Settings&>(settings), control));
    };
    return type;
}

}  // namespace terra::analysis
