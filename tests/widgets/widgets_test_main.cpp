// One QApplication for all widgets tests, offscreen (no display needed). Settings, autosave and
// caches go to a temporary HOME (QStandardPaths test mode inside it), never to the user's
// configuration or the source or build tree; it is removed when the tests end.
#include <gtest/gtest.h>

#include <QApplication>
#include <QDir>
#include <QStandardPaths>
#include <QTemporaryDir>

int main(int argc, char** argv) {
    qputenv("QT_QPA_PLATFORM", "offscreen");
    QTemporaryDir home(QDir::tempPath() + "/terra-widgets-tests-XXXXXX");
    if (!home.isValid()) return 2;
    for (const char* variable :
         {"HOME", "XDG_CONFIG_HOME", "XDG_DATA_HOME", "XDG_CACHE_HOME", "XDG_STATE_HOME"}) {
        qputenv(variable, home.path().toLocal8Bit());
    }
    QStandardPaths::setTestModeEnabled(true);
    QApplication application(argc, argv);
    QApplication::setOrganizationName("TerraStudioTests");
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
