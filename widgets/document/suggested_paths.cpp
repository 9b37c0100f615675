#include "widgets/document/suggested_paths.h"

#include <QDir>
#include <QFileInfo>
#include <QSettings>

namespace terra::ui {
namespace {

constexpr const char* kLastFolderKey = "files/lastFolder";

}  // namespace

QString startFolder(const QString& project_path) {
    if (!project_path.isEmpty()) return QFileInfo(project_path).absolutePath();
    const QString last = QSettings().value(kLastFolderKey).toString();
    if (!last.isEmpty() && QFileInfo(last).isDir()) return last;
    return QDir::homePath();
}

QString suggestedPath(const QString& project_path, const QString& name, const QString& suffix) {
    const QString project =
        project_path.isEmpty() ? QString("untitled") : QFileInfo(project_path).completeBaseName();
    const QString file = name.isEmpty() ? project + suffix : project + "-" + name + suffix;
    return QDir(startFolder(project_path)).filePath(file);
}

void rememberFolder(const QString& path) {
    if (path.isEmpty()) return;
    QSettings().setValue(kLastFolderKey, QFileInfo(path).absolutePath());
}

}  // namespace terra::ui
