#pragma once
/// @file headless_application.h
/// The Qt application object of a headless subcommand (`run`, `render`): QCustomPlot paints with a
/// QPainter and needs one, on the offscreen platform here (no display).

#include <QApplication>
#include <QTemporaryDir>
#include <memory>
#include <optional>

namespace terra::app {

/// Sets the offscreen platform and creates the QApplication; a headless run then prints nothing
/// but its own output. Without XDG_RUNTIME_DIR (a CI machine, ssh, a service), Qt would print
/// "QStandardPaths: XDG_RUNTIME_DIR not set, defaulting to '/tmp/runtime-USER'" on stderr and leave
/// that folder behind: a private runtime folder (mode 0700, as the XDG specification requires) is
/// given instead, and removed when the object is destroyed. A set XDG_RUNTIME_DIR is left alone.
class HeadlessApplication {
public:
    HeadlessApplication();
    HeadlessApplication(const HeadlessApplication&) = delete;
    HeadlessApplication& operator=(const HeadlessApplication&) = delete;

private:
    std::optional<QTemporaryDir> runtime_dir_;  // outlives application_ (declared before it)
    int argc_ = 1;
    char name_[12] = "terrastudio";
    char* argv_[2] = {name_, nullptr};
    std::unique_ptr<QApplication> application_;
};

}  // namespace terra::app
