#pragma once
// The studio's main window: wiring only (panels live in widgets/).

#include <QMainWindow>

#include "core/io/parameters_json.h"

namespace terra::app {

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(const io::PresetLocations& locations, QWidget* parent = nullptr);
};

}  // namespace terra::app
