// The main window's dock layouts (View ▸ Layout; main_window.h). Split from main_window.cpp to
// keep each file small. Every analysis panel is a QDockWidget, and so is each plot the user shows
// in a dock of its own (ui::PlotDocking): the user tears one off, drags it beside another or tabs
// it with one; QMainWindow::saveState keeps that arrangement (closeEvent), with the torn-off
// plots' names ("window/plots").
#include <QDockWidget>
#include <QGuiApplication>
#include <QPointer>
#include <QScreen>
#include <QSettings>
#include <QStatusBar>
#include <QStyle>
#include <QTimer>
#include <algorithm>

#include "app/main_window.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/panels/plot_docking.h"

namespace terra::app {
namespace {

// Widths of the left column [px]: at 1024 px the panels keep ~730 px, enough for every panel's
// controls without a sideways scroll bar (tests/app/main_window_test.cpp measures it).
constexpr int kDefaultColumnWidth = 330;
constexpr int kCompactColumnWidth = 280;
constexpr int kCompactTreeHeight = 120;  // [px]: six rows, the rest scroll
// Width a plot in a dock of its own gets at least beside its panel (side by side) [px].
constexpr int kPlotWidth = 300;

// Tiles: cells of panels tabbed together, as wide as the widest of them needs [px]; rows of
// cells that fit the panel area's width.
struct Cell {
    std::vector<QDockWidget*> docks;
    int width = 0;
};
using Rows = std::vector<std::vector<Cell>>;

// The width of a row's cells and the separators after them [px].
int rowWidth(const std::vector<Cell>& row, int separator) {
    int sum = 0;
    for (const Cell& c : row) sum += c.width + separator;
    return sum;
}

// The docks in order, in `rows_at_most` rows of cells fitting `room` px: each one in a cell of
// its own in the last row while it fits, else in a new row, else tabbed into the cell it widens
// least among those whose row still fits (else the widest cell).
Rows packTiles(const std::vector<QDockWidget*>& docks, int room, int separator,
               std::size_t rows_at_most) {
    Rows rows(1);
    for (QDockWidget* d : docks) {
        const int need = terra::ui::dockMinimumWidth(*d);
        if (rows.back().empty() || rowWidth(rows.back(), separator) + need <= room) {
            rows.back().push_back({{d}, need});
            continue;
        }
        if (rows.size() < rows_at_most) {
            rows.push_back({Cell{{d}, need}});
            continue;
        }
        Cell* best = nullptr;
        int best_growth = 0;
        Cell* widest = nullptr;
        for (auto& row : rows) {
            for (Cell& c : row) {
                if (!widest || c.width > widest->width) widest = &c;
                const int growth = std::max(0, need - c.width);
                if (rowWidth(row, separator) + growth > room) continue;
                if (!best || growth < best_growth) {
                    best = &c;
                    best_growth = growth;
                }
            }
        }
        Cell* cell = best ? best : widest;
        cell->docks.push_back(d);
        cell->width = std::max(cell->width, need);
    }
    return rows;
}

// Sets the widths of cells of docks side by side (a cell: docks tabbed together; its dock in
// front sized). resizeDocks alone left a cell squeezed at times (a row of tabbed panels, under
// Xvfb the second row): when the area is wide enough for every cell's need, the cells' docks
// are held at that need as their minimum until the window has been laid out, then released
// (the widths stay). Never held otherwise: the window must not grow past the screen.
void setWidths(QMainWindow* area, const std::vector<std::vector<QDockWidget*>>& cells,
               const QList<int>& widths, const QList<int>& needs, int row_width) {
    QList<QDockWidget*> fronts;
    for (const auto& cell : cells) fronts << cell.front();
    if (area->width() >= row_width) {
        std::vector<QPointer<QDockWidget>> held;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            for (QDockWidget* d : cells[i]) {
                d->setMinimumWidth(needs[static_cast<int>(i)]);
                held.emplace_back(d);
            }
        }
        QTimer::singleShot(0, area, [held] {
            for (const QPointer<QDockWidget>& d : held)
                if (d) d->setMinimumWidth(0);
        });
    }
    area->resizeDocks(fronts, widths, Qt::Horizontal);
}

std::size_t cellCount(const Rows& rows) {
    std::size_t n = 0;
    for (const auto& row : rows) n += row.size();
    return n;
}

}  // namespace

MainWindow::Layout MainWindow::layoutForScreen() const {
    const QScreen* s = screen() ? screen() : QGuiApplication::primaryScreen();
    if (!s) return Layout::kDefault;
    const QSize available = s->availableGeometry().size();
    return available.width() < 1366 || available.height() < 740 ? Layout::kCompact
                                                                : Layout::kDefault;
}

void MainWindow::restoreWindowState() {
    const QSettings settings;
    // The arrangement the user left, if this studio wrote it; else the one for the screen.
    applyLayout(layoutForScreen());
    restoreState(settings.value("window/state").toByteArray(), kLayoutVersion);
    // The plots the user had in docks of their own, torn off again before the panel area's state
    // is restored: it finds their docks by name and puts them back where they were. A name of
    // no plot (an older or newer studio's) is ignored.
    plot_docking_->restore(settings.value("window/plots").toStringList());
    panel_area_->restoreState(settings.value("window/panels").toByteArray(), kLayoutVersion);
}

void MainWindow::saveWindowState() const {
    QSettings settings;
    settings.setValue("window/geometry", saveGeometry());
    settings.setValue("window/state", saveState(kLayoutVersion));
    settings.setValue("window/plots", plot_docking_->tornOff());
    settings.setValue("window/panels", panel_area_->saveState(kLayoutVersion));
}

int MainWindow::panelAreaWidth(int column) const {
    // The window's width less the left column and the separator beside it (the window may not
    // be laid out yet: the panel area's own width would be stale). Column 0: the Project and
    // Properties panes hidden.
    const int separator = style()->pixelMetric(QStyle::PM_DockWidgetSeparatorExtent);
    return column > 0 ? width() - column - separator : width();
}

void MainWindow::giveThePanelsTheWidth() {
    project_dock_->hide();
    properties_dock_->hide();
    statusBar()->showMessage(
        "The Project and Properties panes are hidden to give the panels the window's width "
        "(View ▸ Panels and panes shows them; Default puts everything back)",
        8000);
}

void MainWindow::applyLayout(Layout layout) {
    chosen_layout_ = layout;
    ui::AnalysisPanel* current = current_;
    const bool column_shown = project_dock_->isVisible() || properties_dock_->isVisible();
    // Default and compact are the panels as built: every plot back in its panel.
    if (layout == Layout::kDefault || layout == Layout::kCompact) plot_docking_->putAllBack();
    std::vector<QDockWidget*> all{project_dock_, properties_dock_};
    all.insert(all.end(), panel_docks_.begin(), panel_docks_.end());
    const std::vector<QDockWidget*> plot_docks = plot_docking_->docks();
    all.insert(all.end(), plot_docks.begin(), plot_docks.end());
    // A width the layout before held (setWidths) is released now, not only when its timer
    // fires: still held, it counted twice in the docks' needs (dockMinimumWidth) and a layout
    // chosen right after another (or on a loaded machine) packed one panel a row.
    for (QDockWidget* d : all) d->setMinimumWidth(0);
    // From scratch: every dock docked and shown (a floating one comes back into the window).
    for (QDockWidget* d : all) d->setFloating(false);
    removeDockWidget(project_dock_);
    removeDockWidget(properties_dock_);
    for (QDockWidget* d : panel_docks_) panel_area_->removeDockWidget(d);
    for (QDockWidget* d : plot_docks) panel_area_->removeDockWidget(d);
    addDockWidget(Qt::LeftDockWidgetArea, project_dock_);
    addDockWidget(Qt::LeftDockWidgetArea, properties_dock_);
    splitDockWidget(project_dock_, properties_dock_, Qt::Vertical);
    for (QDockWidget* d : {project_dock_, properties_dock_}) d->show();
    const int column = layout == Layout::kCompact ? kCompactColumnWidth : kDefaultColumnWidth;
    resizeDocks({properties_dock_}, {column}, Qt::Horizontal);
    // Compact: a short tree, the properties get the height.
    if (layout == Layout::kCompact)
        resizeDocks({project_dock_, properties_dock_}, {kCompactTreeHeight, 500}, Qt::Vertical);
    else
        resizeDocks({project_dock_, properties_dock_}, {170, 500}, Qt::Vertical);
    std::size_t current_index = 0;
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        if (panels_[i] == current) current_index = i;
    }
    if (layout == Layout::kTiled) {
        arrangeTiles(column);
    } else if (layout == Layout::kSideBySide) {
        arrangeSideBySide(current_index, column);
    } else {
        QDockWidget* first = panel_docks_.front();
        panel_area_->addDockWidget(Qt::TopDockWidgetArea, first);
        for (std::size_t i = 1; i < panel_docks_.size(); ++i)
            panel_area_->tabifyDockWidget(first, panel_docks_[i]);
        for (QDockWidget* d : panel_docks_) d->show();
    }
    if (layout == Layout::kSideBySide || layout == Layout::kTiled) {
        setCurrentPanel(current);
        panel_docks_[current_index]->raise();
        // The column just hidden gives the panel area its width only when the window is laid
        // out: the panels' widths set now are shares of the narrower area (a row with tabbed
        // panels came out squeezed). Once more then, the area already as wide.
        // The layout chosen last, not this one: a layout chosen before the re-apply runs (Tiled
        // right after Side by side, the column already hidden) asks for none of its own.
        if (column_shown && !project_dock_->isVisible() && isVisible())
            QTimer::singleShot(0, this, [this] { applyLayout(chosen_layout_); });
    } else {
        showPanel(current ? current->name() : panels_.front()->name());
    }
}

void MainWindow::arrangeSideBySide(std::size_t current_index, int column) {
    const int separator = style()->pixelMetric(QStyle::PM_DockWidgetSeparatorExtent);
    QDockWidget* left = panel_docks_[current_index];
    const int left_width = ui::dockMinimumWidth(*left);
    // Beside it: its plots in docks of their own (one under the other), else the next panel
    // that fits beside it without either scrolling sideways — beside the Project and Properties
    // column, else in the window's whole width (the column hidden). When nothing fits beside it
    // (a 1024 px screen), its plot or the next panel goes under it instead: the panels then
    // share the height, but neither scrolls sideways.
    std::vector<QDockWidget*> right = plot_docking_->docks(panels_[current_index]);
    // A plot needs room for its axes and legend (its dock's minimum) and some for its data.
    const auto plotWidth = [](const QDockWidget* d) {
        return std::max(kPlotWidth, d->minimumSizeHint().width());
    };
    const auto needOf = [this, &plotWidth](const QDockWidget* d) {
        return plot_docking_->panelOf(d) ? plotWidth(d) : ui::dockMinimumWidth(*d);
    };
    const auto fits = [&](const QDockWidget* d, int width) {
        return left_width + separator + needOf(d) <= width;
    };
    int room = 0;
    if (right.empty()) {
        QDockWidget* next = nullptr;
        for (const int width : {panelAreaWidth(column), panelAreaWidth(0)}) {
            for (std::size_t step = 1; step < panel_docks_.size() && !next; ++step) {
                QDockWidget* d = panel_docks_[(current_index + step) % panel_docks_.size()];
                if (fits(d, width)) next = d;
            }
            if (next) break;
        }
        right.push_back(next ? next : panel_docks_[(current_index + 1) % panel_docks_.size()]);
    }
    for (const int width : {panelAreaWidth(column), panelAreaWidth(0)}) {
        room = width;
        if (fits(right.front(), width)) break;
    }
    const bool beside = fits(right.front(), room);
    if (!beside) {
        room = left_width <= panelAreaWidth(column) ? panelAreaWidth(column) : panelAreaWidth(0);
    }
    if (room > panelAreaWidth(column)) giveThePanelsTheWidth();
    panel_area_->addDockWidget(Qt::TopDockWidgetArea, left);
    left->show();
    panel_area_->splitDockWidget(left, right.front(), beside ? Qt::Horizontal : Qt::Vertical);
    right.front()->show();
    for (std::size_t i = 1; i < right.size(); ++i) {
        panel_area_->splitDockWidget(right[i - 1], right[i],
                                     beside ? Qt::Vertical : Qt::Horizontal);
        right[i]->show();
    }
    // The others tabbed with the panel on the left, plots with their own panel.
    for (QDockWidget* d : panel_docks_) {
        if (d == left || d == right.front()) continue;
        panel_area_->tabifyDockWidget(left, d);
        d->show();
    }
    for (QDockWidget* d : plot_docking_->docks()) {
        if (std::find(right.begin(), right.end(), d) != right.end()) continue;
        panel_area_->tabifyDockWidget(plot_docking_->homeOf(plot_docking_->panelOf(d)), d);
        d->show();
    }
    left->raise();
    right.front()->raise();
    if (!beside) return;
    // Each side the width it needs and half the spare width.
    const int right_need = needOf(right.front());
    const int spare = std::max(0, room - separator - left_width - right_need);
    setWidths(panel_area_, {{left}, {right.front()}},
              {left_width + spare / 2, right_need + spare - spare / 2}, {left_width, right_need},
              left_width + separator + right_need);
}

void MainWindow::arrangeTiles(int column) {
    // Two rows (a third would leave each panel less than 200 px of height at 768 px), as many
    // panels in each as fit beside each other without scrolling sideways — beside the Project
    // and Properties column, or in the window's whole width (the column hidden) when that shows
    // more of them or a panel is wider than the room beside the column; the others tabbed with
    // them.
    constexpr std::size_t kRows = 2;
    const int separator = style()->pixelMetric(QStyle::PM_DockWidgetSeparatorExtent);
    int room = panelAreaWidth(column);
    Rows rows = packTiles(panel_docks_, room, separator, kRows);
    const Rows whole = packTiles(panel_docks_, panelAreaWidth(0), separator, kRows);
    const bool overflows = std::any_of(rows.begin(), rows.end(), [&](const auto& row) {
        return rowWidth(row, separator) - separator > room;
    });
    if (cellCount(whole) > cellCount(rows) || overflows) {
        rows = whole;
        room = panelAreaWidth(0);
        giveThePanelsTheWidth();
    }
    QDockWidget* first = rows.front().front().docks.front();
    panel_area_->addDockWidget(Qt::TopDockWidgetArea, first);
    if (rows.size() > 1)
        panel_area_->splitDockWidget(first, rows[1].front().docks.front(), Qt::Vertical);
    for (const auto& row : rows) {
        for (std::size_t i = 1; i < row.size(); ++i)
            panel_area_->splitDockWidget(row[i - 1].docks.front(), row[i].docks.front(),
                                         Qt::Horizontal);
        for (const Cell& c : row) {
            for (std::size_t k = 1; k < c.docks.size(); ++k)
                panel_area_->tabifyDockWidget(c.docks.front(), c.docks[k]);
        }
    }
    // Plots in docks of their own tabbed with their panel.
    for (QDockWidget* d : plot_docking_->docks())
        panel_area_->tabifyDockWidget(plot_docking_->homeOf(plot_docking_->panelOf(d)), d);
    for (QDockWidget* d : panel_docks_) d->show();
    for (QDockWidget* d : plot_docking_->docks()) d->show();
    // Each cell as wide as it needs and an even share of the row's spare width; each cell's
    // first panel in front.
    for (const auto& row : rows) {
        const int spare =
            std::max(0, room - rowWidth(row, separator)) / static_cast<int>(row.size());
        std::vector<std::vector<QDockWidget*>> cells;
        QList<int> widths, needs;
        for (const Cell& c : row) {
            c.docks.front()->raise();
            cells.push_back(c.docks);
            widths << c.width + spare;
            needs << c.width;
        }
        setWidths(panel_area_, cells, widths, needs, rowWidth(row, separator) - separator);
    }
}

}  // namespace terra::app
