#include "widgets/panels/plot_docking.h"

#include <qcustomplot.h>

#include <QDockWidget>
#include <QEvent>
#include <QLabel>
#include <QLayout>
#include <QMainWindow>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QSplitter>
#include <QStackedWidget>
#include <QStyle>
#include <QTabWidget>
#include <QVBoxLayout>
#include <algorithm>

#include "widgets/panels/analysis_panel.h"
#include "widgets/plots/plot_menu.h"

namespace terra::ui {
namespace {

/// The tab widget `page` is a page of, nullptr for none.
QTabWidget* tabsOfPage(const QWidget* page) {
    auto* stack = qobject_cast<QStackedWidget*>(page->parentWidget());
    auto* tabs = stack ? qobject_cast<QTabWidget*>(stack->parentWidget()) : nullptr;
    return tabs && tabs->indexOf(const_cast<QWidget*>(page)) >= 0 ? tabs : nullptr;
}

}  // namespace

int dockMinimumWidth(const QDockWidget& dock) {
    const QWidget* content = dock.widget();
    if (!content) return dock.minimumSizeHint().width();
    // The dock's frame and margins around its content.
    const int frame =
        std::max(0, dock.minimumSizeHint().width() - content->minimumSizeHint().width());
    const auto* area = qobject_cast<const QScrollArea*>(content);
    if (!area || !area->widget()) return content->minimumSizeHint().width() + frame;
    // The vertical scroll bar is counted: a panel shorter than its content shows one, and it
    // must not push the content under a sideways one.
    return area->widget()->minimumSizeHint().width() + 2 * area->frameWidth() +
           area->verticalScrollBar()->sizeHint().width() + frame;
}

PlotDocking::PlotDocking(QMainWindow* area, QObject* parent) : QObject(parent), area_(area) {
    // The right dock area spans the panel area's height: torn-off plots make a column beside
    // the panels (the top area, where the panels are, would otherwise sit above it).
    area_->setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    area_->setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
}

PlotDocking::~PlotDocking() = default;

void PlotDocking::addPanel(AnalysisPanel* panel, QDockWidget* home, const QString& title) {
    panels_.push_back(std::make_unique<Panel>(Panel{panel, home, title}));
    panel->installPlotMenus(
        [this, title](QCustomPlot& plot, PlotMenuHooks& hooks, PlotDockHooks& dock) {
            QCustomPlot* p = &plot;
            // The panel's current plot and table are those of its current tab: a torn-off plot's
            // menu makes its tab current while it runs (the placeholder's), so that Copy data and
            // Export are of this plot.
            hooks.table = [this, p, table = hooks.table] {
                Table t;
                withPlotCurrent(p, [&t, &table] { t = table(); });
                return t;
            };
            hooks.export_plot = [this, p, export_plot = hooks.export_plot] {
                withPlotCurrent(p, export_plot);
            };
            dock.in_own_dock = [this, p] { return dockOf(p) != nullptr; };
            dock.set_own_dock = [this, p](bool own) {
                if (own)
                    tearOff(p);
                else
                    putBack(p);
            };
            dock.home = title;
        });
}

QString PlotDocking::dockName(const AnalysisPanel& panel, const QString& plot_name,
                              const QCustomPlot& plot) {
    const QString key = plot.objectName().isEmpty() ? plot_name : plot.objectName();
    return "plot." + panel.name() + "." + key;
}

const PlotDocking::Panel* PlotDocking::panelWith(const QCustomPlot* plot, QString* name) const {
    for (const auto& entry : panels_) {
        for (const auto& [plot_name, candidate] : entry->panel->plots()) {
            if (candidate != plot) continue;
            if (name) *name = plot_name;
            return entry.get();
        }
    }
    return nullptr;
}

const PlotDocking::Torn* PlotDocking::tornOf(const QCustomPlot* plot) const {
    for (const Torn& t : torn_) {
        if (t.plot == plot) return &t;
    }
    return nullptr;
}

QString PlotDocking::labelOf(const Panel& panel, const QCustomPlot* plot,
                             const QString& name) const {
    // The tab the plot is shown in ("Fx", "Depth profile"), when that tab holds no other plot.
    for (const QWidget* w = plot; w && w != panel.panel; w = w->parentWidget()) {
        QTabWidget* tabs = tabsOfPage(w);
        if (!tabs) continue;
        int plots_in_page = 0;
        for (const auto& [other_name, other] : panel.panel->plots()) {
            if (other == w || w->isAncestorOf(other)) ++plots_in_page;
        }
        if (plots_in_page == 1) return tabs->tabText(tabs->indexOf(const_cast<QWidget*>(w)));
        break;
    }
    return name;
}

QWidget* PlotDocking::placeholderFor(QCustomPlot* plot, const QString& label, const QString& home) {
    auto* placeholder = new QWidget;
    placeholder->setObjectName("plot.placeholder");
    auto* text = new QLabel(label + " is shown in its own dock.", placeholder);
    text->setAlignment(Qt::AlignCenter);
    text->setWordWrap(true);
    auto* back = new QPushButton("Put back", placeholder);
    back->setObjectName("plot.put_back");
    back->setToolTip("Put the plot back here, into " + home);
    connect(back, &QPushButton::clicked, this, [this, plot] { putBack(plot); });
    auto* layout = new QVBoxLayout(placeholder);
    layout->addStretch(1);
    layout->addWidget(text);
    layout->addWidget(back, 0, Qt::AlignHCenter);
    layout->addStretch(1);
    return placeholder;
}

QDockWidget* PlotDocking::tearOff(QCustomPlot* plot) {
    if (QDockWidget* existing = dockOf(plot)) return existing;
    QString name;
    const Panel* panel = panelWith(plot, &name);
    if (!panel) return nullptr;
    const QString label = labelOf(*panel, plot, name);
    Torn torn{panel, plot, {}, {}, {}, {}, {}, {}};
    QWidget* placeholder = placeholderFor(plot, label, panel->title);
    QWidget* parent = plot->parentWidget();
    if (QTabWidget* tabs = tabsOfPage(plot)) {
        // The placeholder takes the plot's tab, at its index: the panel's tabs keep their order
        // (its currentPlot() goes by index) and the tab on screen stays on screen.
        const int index = tabs->indexOf(plot);
        const int current = tabs->currentIndex();
        torn.tabs = tabs;
        torn.tab_text = tabs->tabText(index);
        torn.tab_tooltip = tabs->tabToolTip(index);
        const QSignalBlocker block(tabs);
        tabs->removeTab(index);
        tabs->insertTab(index, placeholder, torn.tab_text);
        tabs->setTabToolTip(index, torn.tab_tooltip);
        tabs->setCurrentIndex(current);
    } else if (auto* splitter = qobject_cast<QSplitter*>(parent)) {
        torn.splitter = splitter;
        splitter->replaceWidget(splitter->indexOf(plot), placeholder);
    } else if (parent && parent->layout()) {
        QLayoutItem* replaced = parent->layout()->replaceWidget(plot, placeholder);
        if (!replaced) {
            delete placeholder;
            return nullptr;
        }
        delete replaced;
    } else {
        delete placeholder;
        return nullptr;
    }
    auto* dock = new QDockWidget(panel->title + " — " + label, area_);
    dock->setObjectName(dockName(*panel->panel, name, *plot));
    dock->setWidget(plot);
    plot->show();
    dock->installEventFilter(this);  // closing it puts the plot back
    torn.dock = dock;
    torn.placeholder = placeholder;
    torn_.push_back(torn);
    place(dock, *panel);
    dock->show();
    AnalysisPanel* owner = panel->panel;
    owner->setPlotOutside(plot, true);
    connect(dock, &QDockWidget::visibilityChanged, owner, [owner, plot](bool visible) {
        if (visible) owner->plotShownOutside(plot);
    });
    owner->plotShownOutside(plot);
    emit changed();
    return dock;
}

QDockWidget* PlotDocking::tearOff(const QString& dock_name) {
    for (const auto& entry : panels_) {
        for (const auto& [name, plot] : entry->panel->plots()) {
            if (dockName(*entry->panel, name, *plot) == dock_name) return tearOff(plot);
        }
    }
    return nullptr;
}

void PlotDocking::place(QDockWidget* dock, const Panel& panel) {
    // Under the plots torn off before, in the column on the right of the panels.
    QDockWidget* above = nullptr;
    for (const Torn& t : torn_) {
        if (t.dock && t.dock != dock && !t.dock->isFloating() && t.dock->isVisible() &&
            area_->dockWidgetArea(t.dock) == Qt::RightDockWidgetArea)
            above = t.dock;
    }
    if (above) {
        area_->splitDockWidget(above, dock, Qt::Vertical);
        return;
    }
    area_->addDockWidget(Qt::RightDockWidgetArea, dock);
    // The panel keeps the width it needs (no sideways scroll bar in it), the plot gets the rest
    // — at least a third of the area.
    if (!panel.home || panel.home->isFloating()) return;
    const int room = area_->width();
    const int separator = area_->style()->pixelMetric(QStyle::PM_DockWidgetSeparatorExtent);
    const int width = std::max(room - dockMinimumWidth(*panel.home) - separator, room / 3);
    area_->resizeDocks({dock}, {width}, Qt::Horizontal);
}

void PlotDocking::putBack(QCustomPlot* plot) {
    const auto it =
        std::find_if(torn_.begin(), torn_.end(), [plot](const Torn& t) { return t.plot == plot; });
    if (it == torn_.end()) return;
    const Torn torn = *it;
    torn_.erase(it);
    QWidget* placeholder = torn.placeholder;
    if (torn.tabs && placeholder && torn.tabs->indexOf(placeholder) >= 0) {
        QTabWidget* tabs = torn.tabs;
        const int index = tabs->indexOf(placeholder);
        const int current = tabs->currentIndex();
        const QSignalBlocker block(tabs);
        tabs->removeTab(index);
        tabs->insertTab(index, plot, torn.tab_text);
        tabs->setTabToolTip(index, torn.tab_tooltip);
        tabs->setCurrentIndex(current);
    } else if (torn.splitter && placeholder) {
        torn.splitter->replaceWidget(torn.splitter->indexOf(placeholder), plot);
        plot->show();
    } else if (placeholder && placeholder->parentWidget() &&
               placeholder->parentWidget()->layout()) {
        delete placeholder->parentWidget()->layout()->replaceWidget(placeholder, plot);
        plot->show();
    }
    if (placeholder) placeholder->deleteLater();
    if (QDockWidget* dock = torn.dock) {
        dock->removeEventFilter(this);
        area_->removeDockWidget(dock);
        dock->deleteLater();
    }
    torn.panel->panel->setPlotOutside(plot, false);
    emit changed();
}

void PlotDocking::putAllBack() {
    while (!torn_.empty()) putBack(torn_.back().plot);
}

bool PlotDocking::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() == QEvent::Close) {
        for (const Torn& t : torn_) {
            if (t.dock != watched) continue;
            putBack(t.plot);  // erases t: nothing of it is read after
            break;
        }
    }
    return QObject::eventFilter(watched, event);
}

QDockWidget* PlotDocking::dockOf(const QCustomPlot* plot) const {
    const Torn* t = tornOf(plot);
    return t ? t->dock.data() : nullptr;
}

std::vector<QDockWidget*> PlotDocking::docks(const AnalysisPanel* panel) const {
    std::vector<QDockWidget*> out;
    for (const Torn& t : torn_) {
        if (t.dock && (!panel || t.panel->panel == panel)) out.push_back(t.dock);
    }
    return out;
}

AnalysisPanel* PlotDocking::panelOf(const QDockWidget* dock) const {
    for (const Torn& t : torn_) {
        if (t.dock == dock) return t.panel->panel;
    }
    return nullptr;
}

QDockWidget* PlotDocking::homeOf(const AnalysisPanel* panel) const {
    for (const auto& entry : panels_) {
        if (entry->panel == panel) return entry->home;
    }
    return nullptr;
}

QStringList PlotDocking::tornOff() const {
    QStringList names;
    for (const Torn& t : torn_) {
        if (t.dock) names << t.dock->objectName();
    }
    return names;
}

int PlotDocking::restore(const QStringList& dock_names) {
    int restored = 0;
    for (const QString& name : dock_names) {
        if (tearOff(name)) ++restored;
    }
    return restored;
}

void PlotDocking::withPlotCurrent(const QCustomPlot* plot, const std::function<void()>& f) const {
    const Torn* torn = tornOf(plot);
    const QWidget* anchor = torn && torn->placeholder ? torn->placeholder.data() : plot;
    // Each tab widget between the plot and its panel, with the tab it showed.
    std::vector<std::pair<QPointer<QTabWidget>, int>> shown;
    for (const QWidget* w = anchor; w && !qobject_cast<const AnalysisPanel*>(w);
         w = w->parentWidget()) {
        QTabWidget* tabs = tabsOfPage(w);
        if (!tabs || tabs->currentWidget() == w) continue;
        shown.emplace_back(QPointer<QTabWidget>(tabs), tabs->currentIndex());
        tabs->setCurrentWidget(const_cast<QWidget*>(w));
    }
    f();
    for (auto it = shown.rbegin(); it != shown.rend(); ++it) {
        if (it->first) it->first->setCurrentIndex(it->second);
    }
}

}  // namespace terra::ui
