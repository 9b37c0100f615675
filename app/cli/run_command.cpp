// `terrastudio run SCRIPT.json --out DIR`: runs a script of the registry's analyses headlessly
// (core/project/script.h reads and checks it whole before anything runs; the analyses, the
// expectations, the report and the manifest are the core's), draws their figures with the
// studio's drawing code and writes the figures, the data, report.md and manifest.json. A failed
// expectation makes the exit code 1, a broken script 2 with nothing written (docs/user-guide.md,
// "Scripted runs").
#include <qcustomplot.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
#include "app/headless_application.h"
#include "core/common/build_info.h"
#include "core/io/atomic_file.h"
#include "core/project/script.h"
#include "widgets/plots/analysis_figures.h"
#include "widgets/plots/plot_export.h"

namespace terra::app {
namespace {

namespace fs = std::filesystem;

struct RunOptions {
    std::string script;
    std::string out = "out";
    std::vector<std::string> formats;  // overrides the script's export.formats
};

class Writer {
public:
    Writer(const fs::path& out, const project::ExportSettings& settings) : out_(out) {
        options_.width = settings.width;
        options_.height = settings.height;
        options_.dpi = settings.dpi;
        formats_ = settings.formats;
    }

    // One figure in every format, drawn on a fresh plot laid out at the export size (a hidden
    // widget gets no resize event; figures with equal axis scales need their final ratio).
    void figure(project::RunRecord& record, const project::ScriptAnalysis& a,
                const analysis::FigureSpec& figure, const analysis::Outcome& outcome,
                const QString& title) {
        QCustomPlot plot;
        plot.resize(options_.width, options_.height);
        plot.setViewport(QRect(0, 0, options_.width, options_.height));
        ui::drawAnalysisFigure(plot, a.type->name, figure.key, a.settings, outcome, title);
        for (const std::string& format : formats_) {
            const fs::path path = out_ / (a.name + figure.file_suffix + "." + format);
            QString error;
            if (!ui::exportPlot(plot, QString::fromStdString(path.string()), options_, &error))
                throw std::runtime_error(error.toStdString());
            std::cout << "wrote " << path.string() << '\n';
            record.images.push_back(path.filename().string());
        }
    }

    void table(project::RunRecord& record, const std::string& stem, const Table& table) {
        const fs::path path = out_ / (stem + ".csv");
        QString error;
        if (!ui::exportTable(table, QString::fromStdString(path.string()), &error))
            throw std::runtime_error(error.toStdString());
        std::cout << "wrote " << path.string() << '\n';
        record.data.push_back(path.filename().string());
    }

    void document(project::RunRecord& record, const std::string& file, const nlohmann::json& json) {
        const fs::path path = out_ / file;
        if (const auto error = io::writeFileAtomically(path, json.dump(2) + "\n"))
            throw std::runtime_error(*error);
        std::cout << "wrote " << path.string() << '\n';
        record.data.push_back(path.filename().string());
    }

private:
    fs::path out_;
    ui::ExportOptions options_;
    std::vector<std::string> formats_;
};

project::RunRecord runOne(const project::ScriptAnalysis& a, Writer& writer,
                          const analysis::Control& control) {
    project::RunRecord record;
    record.name = a.name;
    record.type = a.type->name;
    const auto start = std::chrono::steady_clock::now();
    try {
        const analysis::Outcome outcome = a.type->run(a.settings, a.inputs, control);
        const QString title =
            ui::analysisTitle(a.type->name, a.title, a.inputs, a.settings, outcome);
        // A failed or cancelled run keeps its partial results: they are written all the same.
        // One without any table (a stress field with no equilibrium) has no figure either.
        if (!outcome.tables.empty()) {
            for (const analysis::FigureSpec& figure : a.figures)
                writer.figure(record, a, figure, outcome, title);
        }
        for (const analysis::NamedTable& t : outcome.tables) {
            if (t.file_suffix) writer.table(record, a.name + *t.file_suffix, t.table);
        }
        for (const auto& [suffix, json] : outcome.documents)
            writer.document(record, a.name + suffix, json);
        record.notes = outcome.notes;
        if (outcome.status == analysis::Outcome::Status::kCancelled) {
            record.notes.push_back("cancelled: the rows computed so far");
        } else if (outcome.status == analysis::Outcome::Status::kFailed ||
                   outcome.status == analysis::Outcome::Status::kInvalidInput) {
            record.error = outcome.message.empty() ? "failed" : outcome.message;
        }
        record.outcomes = project::evaluate(a.expectations, outcome);
    } catch (const std::exception& e) {
        record.error = e.what();
    }
    record.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return record;
}

int run(const RunOptions& o, const io::PresetLocations& locations) {
    Result<project::Script> loaded = project::loadScript(o.script, locations);
    if (!loaded) throw InputError(loaded.message());
    project::Script script = std::move(loaded).value();
    std::vector<Issue> issues;
    for (const std::string& f : o.formats) {
        const auto& known = project::imageFormats();
        if (std::find(known.begin(), known.end(), f) == known.end())
            issues.push_back({"--format " + f, "not one of png, svg, pdf"});
    }
    if (!issues.empty()) throw InputError(formatIssues(issues));
    if (!o.formats.empty()) script.export_settings.formats = o.formats;

    for (const char* file : {"report.md", "manifest.json"})
        refuseInputAsOutput("--out", fs::path(o.out) / file, {{"script", o.script}});
    std::error_code ec;
    fs::create_directories(o.out, ec);
    if (ec) throw std::runtime_error("cannot create " + o.out + ": " + ec.message());

    const HeadlessApplication application;  // QCustomPlot paints with a QPainter: it needs one

    Writer writer(o.out, script.export_settings);
    std::vector<project::RunRecord> records;
    const std::string tool = std::string("terrastudio ") + build_info::kVersion;
    // The manifest is written first, marked running, and again after every analysis: a run
    // killed outright (SIGKILL, a power cut) leaves a manifest that says so and lists what was
    // finished, never data files without one. The end of the run rewrites it complete.
    const fs::path manifest_path = fs::path(o.out) / "manifest.json";
    auto writeRunningManifest = [&] {
        nlohmann::json running = project::manifest(script, o.script, records, tool);
        running.update({{"status", "running"},
                        {"note",
                         "the run has not finished (or was killed): the files of the "
                         "analyses not listed here may be partial or from an earlier "
                         "run"}});
        if (const auto error = io::writeFileAtomically(manifest_path, running.dump(2) + "\n"))
            throw std::runtime_error(*error);
    };
    writeRunningManifest();
    const SignalCancellation cancellation;
    for (const project::ScriptAnalysis& a : script.analyses) {
        if (cancellation.requested()) break;
        // One bar per analysis, left on its own line when it ends.
        TerminalProgress progress("run " + a.name + " (" + std::to_string(records.size() + 1) +
                                  "/" + std::to_string(script.analyses.size()) + ")");
        project::RunRecord record =
            runOne(a, writer, analysis::Control{cancellation.flag(), progress.callback()});
        progress.finish();
        if (!record.error.empty())
            std::cout << "FAIL: " << record.name << ": " << record.error << '\n';
        for (const auto& outcome : record.outcomes) {
            std::cout << (outcome.passed ? "pass: " : "FAIL: ") << record.name << ": "
                      << outcome.text << '\n';
        }
        records.push_back(std::move(record));
        writeRunningManifest();
    }
    // Cancelled: what was computed is written and reported; the analysis running at the signal
    // keeps its rows so far (its notes say so), the ones after it are not run.
    std::string cancelled;
    if (cancellation.requested()) {
        cancelled = "Cancelled by " + cancellation.signalName() + ": " +
                    std::to_string(records.size()) + " of " +
                    std::to_string(script.analyses.size()) +
                    " analyses started, the last one possibly incomplete";
    }
    const fs::path out(o.out);
    if (const auto error = io::writeFileAtomically(
            out / "report.md", project::reportMarkdown(script, o.script, records, cancelled))) {
        throw std::runtime_error(*error);
    }
    std::cout << "wrote " << (out / "report.md").string() << '\n';
    nlohmann::json manifest = project::manifest(script, o.script, records, tool, cancelled);
    manifest["status"] = cancelled.empty() ? "completed" : "cancelled";
    if (const auto error = io::writeFileAtomically(manifest_path, manifest.dump(2) + "\n")) {
        throw std::runtime_error(*error);
    }
    std::cout << "wrote " << (out / "manifest.json").string() << '\n';
    if (!cancelled.empty()) exitCancelled(cancellation, cancelled);
    const int failed = project::failureCount(records);
    if (failed > 0) {
        std::cerr << failed << " expectation(s) or analyses failed (see "
                  << (out / "report.md").string() << ")\n";
        return kFailure;
    }
    return kSuccess;
}

}  // namespace

void addRunCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<RunOptions>();
    CLI::App* cmd = app.add_subcommand("run",
                                       "Run a script of analyses headlessly: plots, data, "
                                       "report.md; exit 1 when an expectation fails");
    cmd->add_option("script", options->script, "Script (JSON), see docs/user-guide.md")->required();
    cmd->add_option("--out", options->out, "Output directory")->capture_default_str();
    cmd->add_option("--format", options->formats,
                    "Image formats (png, svg, pdf), overriding the script")
        ->delimiter(',');
    cmd->callback([options, &locations] {
        const int code = run(*options, locations);
        if (code != kSuccess) throw CLI::RuntimeError(code);
    });
}

}  // namespace terra::app
