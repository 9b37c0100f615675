#pragma once
/// @file suggested_paths.h
/// Where the studio's Open, Save and Export dialogs start and the file name they suggest: the
/// project's folder (else the folder last used, else the home folder) and a name made of the
/// project's and the tab's names ("field7-rover-path.png"). Save used to open in whatever folder
/// the program ran from (the installed experiments), Export always at ~/forces.png.

#include <QString>

namespace terra::ui {

/// The project file's folder; without one, the folder last used (rememberFolder), else home.
QString startFolder(const QString& project_path);

/// startFolder() / "<project>-<name><suffix>", the project's file name without its suffix
/// ("untitled" for a new project): suggestedPath("/data/field7.terra", "rover-path", ".png") is
/// "/data/field7-rover-path.png".
QString suggestedPath(const QString& project_path, const QString& name, const QString& suffix);

/// Remembers the folder of `path` (a file just opened, saved or exported) for startFolder().
void rememberFolder(const QString& path);

}  // namespace terra::ui
