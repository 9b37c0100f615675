#pragma once
/// @file preset_names.h
/// Presets shown by their names ("sandy loam", "wheel B"), not their file ids ("sandy-loam"):
/// the id stays what projects, settings and scripts store.

#include <QString>
#include <string>

#include "core/io/parameters_json.h"

class QComboBox;

namespace terra::ui {

/// Where the running studio finds presets (beside its executable, then the standard places).
io::PresetLocations studioPresetLocations();

/// The name a preset gives itself (resources/soils/sandy-loam.json: "sandy loam"); the id for a
/// kind without names or a file that cannot be read. `kind`: "soils", "wheels", ….
QString presetDisplayName(const io::PresetLocations& locations, const char* kind,
                          const std::string& id);

/// Adds one item per preset of `kind`: its name as the text, its id as the item's data (and in
/// the tooltip). Find them with findData(id), read them with currentData().
void addPresetItems(QComboBox* box, const io::PresetLocations& locations, const char* kind);

}  // namespace terra::ui
