#pragma once
/// @file commands.h
/// The headless subcommands of `terrastudio` (docs/cli.md). Each registers itself on the CLI11
/// application; its callback does the work when the subcommand is given, and throws InputError
/// (exit 2) or std::runtime_error (exit 1) on failure.

#include <CLI/CLI.hpp>

#include "core/io/parameters_json.h"

namespace terra::app {

void addWheelCommand(CLI::App& app, const io::PresetLocations& locations);
void addSinkageCommand(CLI::App& app, const io::PresetLocations& locations);
void addSweepCommands(CLI::App& app, const io::PresetLocations& locations);
void addPresetsCommand(CLI::App& app, const io::PresetLocations& locations);
void addRenderCommand(CLI::App& app, const io::PresetLocations& locations);
void addStressesCommand(CLI::App& app, const io::PresetLocations& locations);
void addIdentifyCommands(CLI::App& app, const io::PresetLocations& locations);
void addRunCommand(CLI::App& app, const io::PresetLocations& locations);
/// `gsa` and `bands`: the global studies of core/analysis/global_sensitivity.h.
void addGsaCommands(CLI::App& app, const io::PresetLocations& locations);
void addSimulateCommand(CLI::App& app, const io::PresetLocations& locations);
void addValidateCommand(CLI::App& app, const io::PresetLocations& locations);
/// `compaction`: stress at depth, compaction risk and repeated passes (core/analysis/compaction.h).
void addCompactionCommand(CLI::App& app, const io::PresetLocations& locations);
/// `traction`: the best slip for a soil (core/analysis/traction.h).
void addTractionCommand(CLI::App& app, const io::PresetLocations& locations);

/// `field`: what a field file holds (core/field/field_summary.h).
void addFieldCommand(CLI::App& app, const io::PresetLocations& locations);

}  // namespace terra::app
