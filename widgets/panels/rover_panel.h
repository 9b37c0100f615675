#pragma once
/// @file rover_panel.h
/// Rover scenario panel: a placeholder until the rover simulation (core/dynamics, core/scenario,
/// issue 4) lands; it says what it will show.

#include <QWidget>

namespace terra::ui {

class RoverPanel : public QWidget {
    Q_OBJECT
public:
    explicit RoverPanel(QWidget* parent = nullptr);
};

}  // namespace terra::ui
