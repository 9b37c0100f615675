// terrastudio: the studio GUI when started plainly, headless subcommands otherwise (docs/cli.md).
#include <CLI/CLI.hpp>
#include <QApplication>
#include <iostream>
#include <stdexcept>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/main_window.h"
#include "core/common/build_info.h"
#include "core/project/project.h"

namespace {

int runHeadless(int argc, char** argv) {
    using namespace terra::app;
    const terra::io::PresetLocations locations =
        terra::io::PresetLocations::standard(executableDirectory());
    CLI::App app{"TerraStudio: wheel-soil interaction (terramechanics) for wheeled mobile robots"};
    app.set_version_flag("--version", std::string("terrastudio ") + terra::build_info::kVersion);
    app.require_subcommand(1);
    addWheelCommand(app, locations);
    addSinkageCommand(app, locations);
    addSweepCommands(app, locations);
    addPresetsCommand(app, locations);
    addRenderCommand(app, locations);
    addStressesCommand(app, locations);
    addIdentifyCommands(app, locations);
    addRunCommand(app, locations);
    addSimulateCommand(app, locations);
    addGsaCommands(app, locations);
    addValidateCommand(app, locations);
    makeOptionsStrict(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::RuntimeError& e) {
        return e.get_exit_code();
    } catch (const CLI::ParseError& e) {
        app.exit(e);  // prints the message and usage hint on stderr
        return kBadInput;
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kBadInput;
    } catch (const std::invalid_argument& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kBadInput;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kFailure;
    }
    return kSuccess;
}

// `terrastudio` or `terrastudio [gui] [FILE.terra] [--panel NAME] [--screenshots DIR]`.
// A project named on the command line that cannot be read is a command-line error like any other
// (exit 2, the file, key and value on stderr), found before any window or dialog exists.
int runGui(int argc, char** argv) {
    const terra::io::PresetLocations locations =
        terra::io::PresetLocations::standard(terra::app::executableDirectory());
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--panel" || arg == "--screenshots") {
            ++i;
            continue;
        }
        if (arg.size() > 6 && arg.ends_with(".terra")) {
            const auto project = terra::project::loadProject(arg, &locations);
            if (!project) {
                std::cerr << "error: " << project.message() << '\n';
                return terra::app::kBadInput;
            }
        }
    }
    QApplication application(argc, argv);
    QApplication::setApplicationName("TerraStudio");
    QApplication::setOrganizationName("TerraStudio");
    terra::app::MainWindow window(
        terra::io::PresetLocations::standard(terra::app::executableDirectory()));
    QString panel, screenshots;
    for (int i = 1; i < argc; ++i) {
        const QString arg = QString::fromLocal8Bit(argv[i]);
        if (arg == "--panel" && i + 1 < argc)
            panel = QString::fromLocal8Bit(argv[++i]);
        else if (arg == "--screenshots" && i + 1 < argc)
            screenshots = QString::fromLocal8Bit(argv[++i]);
        else if (arg.endsWith(".terra") && !window.openProject(arg))
            return terra::app::kBadInput;
    }
    if (!panel.isEmpty()) window.showPanel(panel);
    window.show();
    if (!screenshots.isEmpty()) return window.takeScreenshots(screenshots);
    return QApplication::exec();
}

bool isGuiInvocation(int argc, char** argv) {
    if (argc == 1) return true;
    const std::string first = argv[1];
    return first == "gui" || (first.size() > 6 && first.ends_with(".terra"));
}

}  // namespace

int main(int argc, char** argv) {
    // The GUI when started plainly; headless subcommands otherwise (chosen before any Qt object).
    if (isGuiInvocation(argc, argv)) return runGui(argc, argv);
    return runHeadless(argc, argv);
}
