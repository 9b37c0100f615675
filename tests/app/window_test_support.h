#pragma once
// What the main window's tests share: the resources folder and a shown, active window.

#include <gtest/gtest.h>

#include <QAction>
#include <QSignalSpy>
#include <QTest>

#include "app/main_window.h"

namespace terra::app::test {

inline io::PresetLocations resources() { return {{TERRA_RESOURCE_DIR}}; }

/// A main window on the repository's resources, shown and active.
struct Studio {
    Studio() : window(resources()) {
        window.show();
        window.activateWindow();
        EXPECT_TRUE(QTest::qWaitForWindowActive(&window));
    }
    MainWindow window;
    QAction* action(const QString& name) { return window.findChild<QAction*>(name); }
    template <typename Panel>
    Panel* panel() {
        return window.findChild<Panel*>();
    }
    /// File ▸ Save, as a user presses it, then waits for its results to be written (off the GUI
    /// thread): what that write reported, empty when it succeeded.
    QString saveAndWaitForResults() {
        QSignalSpy saved(&window, &MainWindow::resultsSaved);
        action("action.save")->trigger();
        if (saved.isEmpty()) {
            EXPECT_TRUE(saved.wait(30000)) << "the results were not written";
        }
        return saved.isEmpty() ? QString("not written") : saved.front().at(1).toString();
    }
};

}  // namespace terra::app::test
