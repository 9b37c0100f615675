// The main window's dock layouts (View ▸ Layout; main_window.h). Split from main_window.cpp to
// keep each file small. Every analysis panel is a QDockWidget: the user tears one off, drags it
// beside another or tabs it with one; QMainWindow::saveState keeps that arrangement (closeEvent).
#include <QDockWidget>
#include <QGuiApplication>
#include <QScreen>

#include "app/main_window.h"
#include "widgets/panels/analysis_panel.h"

namespace terra::app {
namespace {

// Widths of the left column [px]: at 1024 px the panels keep ~730 px, enough for every panel's
// controls without a sideways scroll bar (tests/app/main_window_test.cpp measures it).
constexpr int kDefaultColumnWidth = 330;
constexpr int kCompactColumnWidth = 280;
constexpr int kCompactTreeHeight = 120;  // [px]: six rows, the rest scroll

}  // namespace

MainWindow::Layout MainWindow::layoutForScreen() const {
    const QScreen* s = screen() ? screen() : QGuiApplication::primaryScreen();
    if (!s) return Layout::kDefault;
    const QSize available = s->availableGeometry().size();
    return available.width() < 1366 || available.height() < 740 ? Layout::kCompact
                                                                : Layout::kDefault;
}

void MainWindow::applyLayout(Layout layout) {
    ui::AnalysisPanel* current = current_;
    std::vector<QDockWidget*> all{project_dock_, properties_dock_};
    all.insert(all.end(), panel_docks_.begin(), panel_docks_.end());
    // From scratch: every dock docked and shown (a floating one comes back into the window).
    for (QDockWidget* d : all) d->setFloating(false);
    removeDockWidget(project_dock_);
    removeDockWidget(properties_dock_);
    for (QDockWidget* d : panel_docks_) panel_area_->removeDockWidget(d);
    addDockWidget(Qt::LeftDockWidgetArea, project_dock_);
    addDockWidget(Qt::LeftDockWidgetArea, properties_dock_);
    splitDockWidget(project_dock_, properties_dock_, Qt::Vertical);
    QDockWidget* first = panel_docks_.front();
    panel_area_->addDockWidget(Qt::TopDockWidgetArea, first);
    std::size_t current_index = 0;
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        if (panels_[i] == current) current_index = i;
    }
    if (layout == Layout::kTiled) {
        // Two rows: the first half of the panels above, the rest below, each row split evenly.
        const std::size_t per_row = (panel_docks_.size() + 1) / 2;
        QDockWidget* below = panel_docks_[per_row];
        panel_area_->splitDockWidget(first, below, Qt::Vertical);
        for (std::size_t i = 1; i < panel_docks_.size(); ++i) {
            if (i == per_row) continue;
            panel_area_->splitDockWidget(panel_docks_[i - 1], panel_docks_[i], Qt::Horizontal);
        }
    } else if (layout == Layout::kSideBySide) {
        // The current panel on the left, the next one on the right; the others tabbed with it.
        QDockWidget* left = panel_docks_[current_index];
        QDockWidget* right = panel_docks_[(current_index + 1) % panel_docks_.size()];
        if (left != first) {
            panel_area_->removeDockWidget(first);
            panel_area_->addDockWidget(Qt::TopDockWidgetArea, left);
        }
        panel_area_->splitDockWidget(left, right, Qt::Horizontal);
        for (QDockWidget* d : panel_docks_) {
            if (d != left && d != right) panel_area_->tabifyDockWidget(right, d);
        }
        right->raise();
    } else {
        for (std::size_t i = 1; i < panel_docks_.size(); ++i)
            panel_area_->tabifyDockWidget(first, panel_docks_[i]);
    }
    for (QDockWidget* d : all) d->show();
    const int column = layout == Layout::kCompact ? kCompactColumnWidth : kDefaultColumnWidth;
    resizeDocks({properties_dock_}, {column}, Qt::Horizontal);
    // Compact: a short tree, the properties get the height.
    if (layout == Layout::kCompact)
        resizeDocks({project_dock_, properties_dock_}, {kCompactTreeHeight, 500}, Qt::Vertical);
    else
        resizeDocks({project_dock_, properties_dock_}, {170, 500}, Qt::Vertical);
    if (layout == Layout::kSideBySide || layout == Layout::kTiled) {
        setCurrentPanel(current);
        panel_docks_[current_index]->raise();
    } else {
        showPanel(current ? current->name() : panels_.front()->name());
    }
}

}  // namespace terra::app
