// `terrastudio field`: what a field file holds before any wheel drives on it — extent, heights,
// slopes and the area of each soil class — and the slope map (core/field/field_summary.h;
// docs/field.md).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "core/analysis/traversability.h"
#include "core/common/range.h"
#include "core/io/csv.h"
#include "core/io/field_json.h"
#include "core/io/json_reader.h"
#include "core/io/raster_io.h"
#include "core/scenario/scenario_json.h"

namespace terra::app {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

struct FieldOptions {
    std::string file;
    bool json = false;
    std::string out;
    std::string slope_map;
    std::string traversability;
    std::string robot = "default";
    std::optional<int> headings;
    std::optional<double> cell_m;
};

// The settings keys the flags set, and the flags' names for the reader's messages.
const std::vector<std::pair<std::string, std::string>>& fieldFlagNames() {
    static const std::vector<std::pair<std::string, std::string>> names{{"headings", "--headings"},
                                                                        {"cell_m", "--cell"}};
    return names;
}

void printText(std::ostream& out, const field::FieldSummary& s) {
    out << (s.name.empty() ? "field" : s.name) << ": " << formatNumber(s.x_max_m - s.x_min_m)
        << " x " << formatNumber(s.y_max_m - s.y_min_m) << " m (x " << formatNumber(s.x_min_m)
        << " to " << formatNumber(s.x_max_m) << ", y " << formatNumber(s.y_min_m) << " to "
        << formatNumber(s.y_max_m) << ")\n";
    if (s.height_min_m) {
        out << "height " << fixed(*s.height_min_m, 3) << " to " << fixed(*s.height_max_m, 3)
            << " m on " << formatNumber(s.height_cell_m) << " m cells; slope max "
            << fixed(s.max_slope_rad * kDeg, 2) << " deg, mean "
            << fixed(s.mean_slope_rad * kDeg, 2) << " deg\n";
    } else {
        out << "flat (no height map)\n";
    }
    if (!s.classes.empty()) {
        out << "soil classes on " << formatNumber(s.class_cell_m) << " m cells:\n";
        out << "  code  label                 soil                              profile"
               "                area [m2]   share\n";
        for (const field::ClassArea& c : s.classes) {
            char line[256];
            std::snprintf(line, sizeof line, "  %4d  %-20s  %-32s  %-20s  %9s  %5s %%\n", c.code,
                          c.label.c_str(), c.soil.c_str(),
                          c.profile.empty() ? "-" : c.profile.c_str(), fixed(c.area_m2, 1).c_str(),
                          fixed(c.share * 100.0, 1).c_str());
            out << line;
        }
    }
    if (!s.parameters.empty()) {
        out << "parameter rasters:";
        for (const std::string& p : s.parameters) out << ' ' << p;
        out << '\n';
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
    cmd->add_option(
        "--slope-map", o.slope_map,
        "Write the steepest slope [deg] at the height map's cells (.asc, .csv or .tif)");
    cmd->add_option("--traversability", o.traversability,
                    "Write the traversability map before driving: .csv (x_m, y_m, heading_deg, "
                    "grade_deg, slip, status per cell and heading) or .asc/.tif (the largest "
                    "slip over the headings; no data where every heading stalls) or .png (that "
                    "map as a picture with its legend, stalling cells darkest)");
    cmd->add_option("--robot", o.robot, "The robot of --traversability (default: default)");
    cmd->add_option("--headings", o.headings, "Headings of --traversability (default 8)");
    cmd->add_option("--cell", o.cell_m, "Cell of --traversability [m] (default: the height map's)");
    cmd->callback([options, &locations] {
        const FieldOptions& o = *options;
        refuseInputAsOutput("--out", o.out, {{"field", o.file}});
        refuseInputAsOutput("--slope-map", o.slope_map, {{"field", o.file}});
        refuseInputAsOutput("--traversability", o.traversability, {{"field", o.file}});
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
        std::optional<analysis::TraversabilityResult> trav;
        if (!o.traversability.empty()) {
            Result<dynamics::RobotParameters> robot = scenario::resolveRobot(locations, o.robot);
            if (!robot) throw InputError("--robot: " + robot.message());
            nlohmann::json object = nlohmann::json::object();
            if (o.headings) object["headings"] = *o.headings;
            if (o.cell_m) object["cell_m"] = *o.cell_m;
            std::vector<Issue> issues;
            io::ObjectReader reader(object, issues);
            analysis::TraversabilitySettings settings;
            analysis::readTraversabilitySettings(reader, settings);
            reader.finish();
            if (!issues.empty()) {
                nameFlags(issues, fieldFlagNames());
                throw InputError(formatIssues(issues));
            }
            trav = analysis::computeTraversability(file->map, *robot, settings);
            const std::string ext = std::filesystem::path(o.traversability).extension().string();
            if (ext == ".asc" || ext == ".tif" || ext == ".tiff") {
                if (std::optional<std::string> error =
                        io::writeRaster(o.traversability, trav->worst_slip, "slip"))
                    throw std::runtime_error(*error);
            } else if (ext == ".png") {
                if (std::optional<std::string> error =
                        io::writePng(o.traversability, analysis::traversabilityImage(*trav)))
                    throw std::runtime_error(*error);
            } else {
                writeOutput(o.traversability,
                            io::toCsv(analysis::traversabilityTable(*trav, file->map)));
            }
        }
        if (o.json) {
            nlohmann::json j = io::toJson(summary);
            if (trav) j["traversability"] = analysis::toJson(*trav);
            writeOutput(o.out, j.dump(2) + "\n");
        } else {
            std::ostringstream text;
            printText(text, summary);
            if (trav) printSummary(text, analysis::traversabilitySummary(*trav));
            writeOutput(o.out, text.str());
        }
    });
}

}  // namespace terra::app
