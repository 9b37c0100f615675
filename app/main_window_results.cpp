// The main window's saved results: shown when a project is opened (main_window.h). Split from
// main_window.cpp to keep each file small; the reading and the restoring are the widgets' and
// panels' (widgets/document/saved_results_reader.h, AnalysisPanel::restoreResult).
#include <QDockWidget>
#include <QStatusBar>
#include <algorithm>

#include "app/main_window.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/identification_panel.h"

namespace terra::app {

void MainWindow::showSavedResults(const QString& path,
                                  const Result<project::SavedResults>& results) {
    QStringList shown, not_shown;
    auto title = [this](std::size_t i, const std::string& section) {
        const std::string part = section.substr(panels_[i]->name().size());
        return panel_docks_[i]->windowTitle() +
               (part.empty() ? QString() : " (" + QString::fromStdString(part.substr(1)) + ")");
    };
    bool identified = false;
    if (results) {
        // The identification first: the global study's "identified soil" source depends on it.
        std::vector<std::size_t> order(panels_.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::stable_partition(order.begin(), order.end(),
                              [this](std::size_t i) { return panels_[i] == identification_; });
        for (const std::size_t i : order) {
            const std::string name = panels_[i]->name().toStdString();
            for (const auto& [section, saved] : results->panels) {
                if (section != name && !section.starts_with(name + ".")) continue;
                const ui::AnalysisPanel::Restored outcome =
                    panels_[i]->restoreResult(section, saved);
                if (outcome.shown()) {
                    shown << title(i, section);
                    // The fit (not the streaming playback) is what the global study may use.
                    identified = identified || section == identification_->name().toStdString();
                } else {
                    not_shown << title(i, section) + ": " + QString::fromStdString(outcome.message);
                }
            }
        }
        for (const Issue& issue : results->unreadable)
            not_shown << QString::fromStdString(issue.where + ": " + issue.message);
    }
    for (ui::AnalysisPanel* panel : panels_) panel->holdUpdates(false);
    reading_results_ = false;
    if (identified) shareIdentification();
    QString message = "Opened " + path;
    if (!results) {
        message += "; its saved results cannot be read and are not shown: " +
                   QString::fromStdString(results.message());
    } else {
        if (!shown.isEmpty())
            message += QString(" with its saved results (%1)").arg(shown.join(", "));
        if (!not_shown.isEmpty())
            message +=
                QString("; not shown (computed again when asked): %1").arg(not_shown.join("; "));
    }
    statusBar()->showMessage(message, results && not_shown.isEmpty() ? 6000 : 12000);
    emit savedResultsShown();
}

void MainWindow::shareIdentification() {
    const analysis::IdentificationResult& r = identification_->result();
    if (r.report && r.report->usable())
        global_->setIdentification(r.identified, r.report->uncertainty);
}

}  // namespace terra::app
