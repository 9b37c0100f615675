#include "app/headless_application.h"

#include <QDir>
#include <stdexcept>

namespace terra::app {

HeadlessApplication::HeadlessApplication() {
    qputenv("QT_QPA_PLATFORM", "offscreen");
    if (qEnvironmentVariableIsEmpty("XDG_RUNTIME_DIR")) {
        runtime_dir_.emplace(QDir::tempPath() + "/terrastudio-runtime-XXXXXX");
        if (!runtime_dir_->isValid()) {
            throw std::runtime_error("cannot create a runtime folder in " +
                                     QDir::tempPath().toStdString() + ": " +
                                     runtime_dir_->errorString().toStdString());
        }
        qputenv("XDG_RUNTIME_DIR", runtime_dir_->path().toLocal8Bit());
    }
    application_ = std::make_unique<QApplication>(argc_, argv_);
}

}  // namespace terra::app
