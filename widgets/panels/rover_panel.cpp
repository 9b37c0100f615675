#include "widgets/panels/rover_panel.h"

#include <QLabel>
#include <QVBoxLayout>

namespace terra::ui {

RoverPanel::RoverPanel(QWidget* parent) : QWidget(parent) {
    auto* label = new QLabel(
        "<h3>Rover scenario</h3>"
        "<p>Not available in this build: the rover simulation (core/dynamics, core/scenario, issue 4) "
        "has not landed yet.</p>"
        "<p>When it does, this panel edits a scenario, runs it with a progress bar and cancel, and shows the "
        "path, yaw, velocities, per-wheel slip and forces (Figs. 3.7–3.15) with a time scrubber and a top-down "
        "view of the robot on the soil patches.</p>",
        this);
    label->setWordWrap(true);
    label->setAlignment(Qt::AlignTop | Qt::AlignLeft);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(label);
}

}  // namespace terra::ui
