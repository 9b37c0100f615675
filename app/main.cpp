// terrastudio: the studio GUI when started plainly, headless subcommands otherwise (docs/cli.md).
#include <CLI/CLI.hpp>
#include <QApplication>
#include <algorithm>
#include <iostream>
#include <stdexcept>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/main_window.h"
#include "core/common/build_info.h"
#include "core/common/issue.h"
#include "core/common/quoted.h"
#include "core/project/project.h"

namespace {

// "'whee' is not a subcommand; did you mean wheel? …" when the first argument is neither a
// subcommand nor an option of the program itself; "" otherwise.
std::string unknownSubcommand(CLI::App& app, int argc, char** argv) {
    if (argc < 2) return {};
    const std::string first = argv[1];
    std::vector<std::string> names;
    for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
        names.push_back(command->get_name());
    if (std::find(names.begin(), names.end(), first) != names.end()) return {};
    if (first == "--help" || first == "-h" || first == "--version") return {};
    std::string all;
    for (const std::string& name : names) all += (all.empty() ? "" : ", ") + name;
    const std::string near = terra::nearestName(first, names);
    const std::string what = !first.empty() && first[0] == '-'
                                 ? terra::quoteText(first) + " comes before any subcommand"
                                 : terra::quoteText(first) + " is not a subcommand";
    return what + (near.empty() ? "" : "; did you mean " + near + "?") + " (subcommands: " + all +
           "; terrastudio SUBCOMMAND --help for its options)";
}

// "--slp is not an option of wheel; did you mean --slip?" for each unknown option a parse left
// over (CLI::ExtrasError), or "" when none is a --flag.
std::string unknownOptions(const CLI::App& app) {
    const CLI::App* command = nullptr;
    for (const CLI::App* sub : app.get_subcommands()) command = sub;
    if (command == nullptr) return {};
    std::vector<std::string> flags;
    for (const CLI::Option* option : command->get_options()) {
        for (const std::string& name : option->get_lnames()) flags.push_back("--" + name);
    }
    std::string out;
    for (const std::string& extra : app.remaining(true)) {
        if (extra.rfind("--", 0) != 0) continue;
        const std::string flag = extra.substr(0, extra.find('='));
        const std::string near = terra::nearestName(flag, flags);
        out += std::string(out.empty() ? "" : "\n") + terra::quoteText(flag) +
               " is not an option of " + command->get_name() +
               (near.empty() ? "" : "; did you mean " + near + "?");
    }
    return out.empty()
               ? out
               : out + "\n(terrastudio " + command->get_name() + " --help lists its options)";
}

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
    addCompactionCommand(app, locations);
    addTractionCommand(app, locations);
    addFieldCommand(app, locations);
    makeOptionsStrict(app);
    // CLI11 answers an unknown first word with "A subcommand is required": name it instead.
    if (const std::string problem = unknownSubcommand(app, argc, argv); !problem.empty()) {
        std::cerr << "error: " << problem << '\n';
        return kBadInput;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::RuntimeError& e) {
        return e.get_exit_code();
    } catch (const CLI::ExtrasError& e) {
        if (const std::string named = unknownOptions(app); !named.empty()) {
            std::cerr << "error: " << named << '\n';
            return kBadInput;
        }
        app.exit(e);
        return kBadInput;
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
