#include "app/main_window.h"

#include <QApplication>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>

#include "widgets/panels/forces_panel.h"

namespace terra::app {

MainWindow::MainWindow(const io::PresetLocations& locations, QWidget* parent) : QMainWindow(parent) {
    setWindowTitle("TerraStudio");
    auto* panel = new ui::ForcesPanel(locations, this);
    setCentralWidget(panel);
    QMenu* file = menuBar()->addMenu("&File");
    file->addAction("&Quit", QKeySequence::Quit, qApp, &QApplication::quit);
    QMenu* help = menuBar()->addMenu("&Help");
    help->addAction("&About", this, [this] {
        QMessageBox::about(this, "About TerraStudio",
                           "TerraStudio 0.1: wheel–soil interaction for agricultural robots.\n"
                           "Model: thesis chapter 2 with the errata of MODEL-NOTES.");
    });
    connect(panel, &ui::ForcesPanel::sweepFinished, this,
            [this, panel] { statusBar()->showMessage(QString("Sweep: %1 points").arg(panel->result().table.rows.size()), 3000); });
    resize(1280, 800);
}

}  // namespace terra::app
