#pragma once
// Helpers of the widgets tests: the resources, waiting for a panel's result.
#include <QSignalSpy>

#include "core/io/parameters_json.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/panels/forces_panel.h"

namespace terra::ui::test {

inline io::PresetLocations resources() { return {{TERRA_RESOURCE_DIR}}; }

/// Waits until the panel shows a result (true) or fails / times out (false).
inline bool waitForResult(AnalysisPanel& panel, int timeout_ms = 30000) {
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    return shown.wait(timeout_ms);
}

/// A document on sandy loam and wheel A, clean.
inline void resetToDefault(ProjectDocument& document) {
    document.reset(ProjectDocument::defaultProject(resources()));
}

/// The forces panel's plot named `name` (its figure id), or nullptr.
inline QCustomPlot* namedPlot(ForcesPanel& panel, const QString& name) {
    for (const auto& [n, plot] : panel.plots()) {
        if (n == name) return plot;
    }
    return nullptr;
}

/// The graph of `plot` whose legend name is exactly `name`, or nullptr.
inline QCPGraph* graphNamed(const QCustomPlot& plot, const QString& name) {
    for (int i = 0; i < plot.graphCount(); ++i) {
        if (plot.graph(i)->name() == name) return plot.graph(i);
    }
    return nullptr;
}

}  // namespace terra::ui::test
