// `terrastudio field`: what a field file holds before any wheel drives on it — extent, heights,
// slopes and the area of each soil class — and the slope map (core/field/field_summary.h;
// docs/field.md).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "core/common/range.h"
#include "core/io/field_json.h"
#include "core/io/raster_io.h"

namespace terra::app {
namespace {

struct FieldOptions {
    std::string file;
    bool json = false;
    std::string out;
    std::string slope_map;
};

constexpr double kDeg = 180.0 / 3.14159265358979323846;

void printText(const field::FieldSummary& s) {
    std::cout << (s.name.empty() ? "field" : s.name) << ": " << formatNumber(s.x_max_m - s.x_min_m)
              << " x " << formatNumber(s.y_max_m - s.y_min_m) << " m (x " << formatNumber(s.x_min_m)
              << " to " << formatNumber(s.x_max_m) << ", y " << formatNumber(s.y_min_m) << " to "
              << formatNumber(s.y_max_m) << ")\n";
    if (s.height_min_m) {
        std::cout << "height " << fixed(*s.height_min_m, 3) << " to " << fixed(*s.height_max_m, 3)
                  << " m on " << formatNumber(s.height_cell_m) << " m cells; slope max "
                  << fixed(s.max_slope_rad * kDeg, 2) << " deg, mean "
                  << fixed(s.mean_slope_rad * kDeg, 2) << " deg\n";
    } else {
        std::cout << "flat (no height map)\n";
    }
    if (!s.classes.empty()) {
        std::cout << "soil classes on " << formatNumber(s.class_cell_m) << " m cells:\n";
        std::cout << "  code  label                 soil                              profile"
                     "                area [m2]   share\n";
        for (const field::ClassArea& c : s.classes) {
            char line[256];
            std::snprintf(line, sizeof line, "  %4d  %-20s  %-32s  %-20s  %9s  %5s %%\n", c.code,
                          c.label.c_str(), c.soil.c_str(),
                          c.profile.empty() ? "-" : c.profile.c_str(), fixed(c.area_m2, 1).c_str(),
                          fixed(c.share * 100.0, 1).c_str());
            std::cout << line;
        }
    }
    if (!s.parameters.empty()) {
        std::cout << "parameter rasters:";
        for (const std::string& p : s.parameters) std::cout << ' ' << p;
        std::cout << '\n';
    }
}

}  // namespace

void addFieldCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<FieldOptions>();
    FieldOptions& o = *options;
    CLI::App* cmd = app.add_subcommand(
        "field",
        "What a field file holds: extent, heights, slopes and the area of each soil class "
        "(docs/field.md)");
    cmd->add_option("file", o.file, "The field file (JSON naming its rasters and legend)")
        ->required();
    cmd->add_flag("--json", o.json,
                  "JSON: name, extent_m, height_m, max_slope_deg, mean_slope_deg, classes, "
                  "parameters");
    cmd->add_option("--out", o.out, "Write the summary to this file instead of stdout");
    cmd->add_option("--slope-map", o.slope_map,
                    "Write the steepest slope [deg] at the height map's cells (.asc or .csv)");
    cmd->callback([options, &locations] {
        const FieldOptions& o = *options;
        refuseInputAsOutput("--out", o.out, {{"field", o.file}});
        refuseInputAsOutput("--slope-map", o.slope_map, {{"field", o.file}});
        Result<io::FieldFile> file = io::loadField(o.file, locations);
        if (!file) throw InputError(file.message());
        const field::FieldSummary summary = field::summarize(file->map, file->labels);
        if (!o.slope_map.empty()) {
            const std::optional<field::Raster> slope = field::slopeRaster(file->map);
            if (!slope) throw InputError("--slope-map: " + o.file + " has no height map");
            if (std::optional<std::string> error =
                    io::writeRaster(o.slope_map, *slope, "slope_deg"))
                throw std::runtime_error(*error);
        }
        if (o.json) {
            writeOutput(o.out, io::toJson(summary).dump(2) + "\n");
        } else if (!o.out.empty()) {
            std::ostringstream text;
            std::streambuf* old = std::cout.rdbuf(text.rdbuf());
            printText(summary);
            std::cout.rdbuf(old);
            writeOutput(o.out, text.str());
        } else {
            printText(summary);
        }
    });
}

}  // namespace terra::app
