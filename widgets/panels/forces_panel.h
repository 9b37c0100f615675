#pragma once
/// @file forces_panel.h
/// The forces-versus-slip panel (Figs. 2.18–2.26): soil, wheel, load and model on the left, one
/// plot per quantity in tabs. Every edit recomputes the sweep off the GUI thread (QtConcurrent);
/// results of a superseded edit are dropped by revision number.

#include <QFutureWatcher>
#include <QWidget>
#include <vector>

#include "core/analysis/sweep.h"
#include "core/io/parameters_json.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QTabWidget;
class QTimer;
class QCustomPlot;

namespace terra::ui {

class ForcesPanel : public QWidget {
    Q_OBJECT
public:
    explicit ForcesPanel(io::PresetLocations locations, QWidget* parent = nullptr);

    /// Selects a soil and wheel preset by name (false when unknown).
    bool selectPresets(const QString& soil, const QString& wheel);

    /// The last completed sweep (empty before the first one finishes).
    const analysis::SweepResult& result() const { return result_; }

signals:
    void sweepFinished();  ///< a new result is on screen

private:
    struct Computation {
        int revision = 0;
        analysis::SweepResult result;
        QString error;
    };

    void scheduleUpdate();
    void startSweep();
    void showResult(const Computation& computation);

    io::PresetLocations locations_;
    QComboBox* soil_;
    QComboBox* wheel_;
    QDoubleSpinBox* load_;
    QComboBox* model_;
    QLabel* status_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*> plots_;
    QTimer* debounce_;
    QFutureWatcher<Computation> watcher_;
    int revision_ = 0;
    analysis::SweepResult result_;
};

}  // namespace terra::ui
