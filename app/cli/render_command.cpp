// `terrastudio render`: the default analysis of the studio (the forces panel), rendered
// headlessly: a CSV of the sweep and one PNG per quantity, written atomically into --out.
#include <qcustomplot.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/settings_flags.h"
#include "app/cli/signals.h"
#include "app/headless_application.h"
#include "core/analysis/forces.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::app {
namespace {

struct RenderOptions {
    ModelOptions model;
    double load_n = analysis::OperatingConditions{}.load_n;
    std::string out = "out";
    int width = 1200;
    int height = 800;
};

int render(const RenderOptions& o, const io::PresetLocations& locations) {
    refuseInputAsOutput("--out", std::filesystem::path(o.out) / "forces-vs-slip.csv",
                        o.model.inputFiles());
    analysis::Inputs inputs = o.model.inputs(locations);
    inputs.conditions.load_n = o.load_n;
    // The model flags as the forces' settings object, read by their reader (exit 2 names the flag).
    nlohmann::json object = nlohmann::json::object();
    addModelChoices(o.model, object);
    const analysis::ForcesSettings settings =
        readFlagSettings<analysis::ForcesSettings>(object, analysis::readForcesSettings, {});
    const SignalCancellation cancellation;
    TerminalProgress progress("render");
    const analysis::ForcesResult result =
        analysis::computeForceSweep(inputs, settings, {cancellation.flag(), progress.callback()});
    progress.finish();
    const soil::SoilParameters& soil = inputs.soil;
    const wheel::WheelParameters& wheel = inputs.wheel;
    printLines(result.warnings, "warning: ");

    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) throw std::runtime_error("cannot create " + o.out + ": " + ec.message());
    const std::filesystem::path dir(o.out);
    const std::filesystem::path csv = dir / "forces-vs-slip.csv";
    // A cancelled sweep is written and drawn as far as it got; the CSV says so in a last comment.
    const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                             std::to_string(result.table.rows.size()) + " rows";
    if (const auto error = io::writeFileAtomically(
            csv, io::toCsv(result.table) + (result.cancelled ? "# " + note + "\n" : ""))) {
        throw std::runtime_error(*error);
    }
    std::cout << "wrote " << csv.string() << '\n';

    const HeadlessApplication application;  // QCustomPlot paints with a QPainter: it needs one
    QCustomPlot plot;
    plot.resize(o.width, o.height);
    const QString title = QString::fromStdString(soil.name + ", " + wheel.name + ", W = ") +
                          QString::number(o.load_n) + " N";
    for (const ui::SweepQuantity& quantity : ui::sweepQuantities()) {
        ui::plotSweep(plot, result.table, quantity, title);
        const std::filesystem::path png = dir / (quantity.column + "-vs-slip.png");
        QString error;
        if (!ui::exportPng(plot, QString::fromStdString(png.string()), o.width, o.height, &error)) {
            throw std::runtime_error(error.toStdString());
        }
        std::cout << "wrote " << png.string() << '\n';
    }
    if (result.cancelled) exitCancelled(cancellation, "render: sweep " + note);
    return kSuccess;
}

}  // namespace

void addRenderCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Render the forces-vs-slip analysis headlessly: CSV + PNG plots into --out");
    options->model.addTo(*cmd);
    cmd->add_option("--load", options->load_n, "Wheel load W [N]")->capture_default_str();
    cmd->add_option("--out", options->out, "Output directory")->capture_default_str();
    cmd->add_option("--width", options->width, "Image width [px]")->check(CLI::Range(200, 8000));
    cmd->add_option("--height", options->height, "Image height [px]")->check(CLI::Range(200, 8000));
    cmd->callback([options, &locations] {
        std::vector<Issue> issues;
        const FieldInfo& load = contact::loadField();
        if (!checkRange(issues, "--load", options->load_n, load.range, load.displayUnit())) {
            throw InputError(formatIssues(issues));
        }
        render(*options, locations);
    });
}

}  // namespace terra::app
