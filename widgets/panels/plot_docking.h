#pragma once
/// @file plot_docking.h
/// Any plot of an analysis panel in a dock of its own (issue 27): "Show in its own dock" in the
/// plot's right-click menu moves the plot itself — the same QCustomPlot, so the panel keeps
/// drawing into it and its export and Copy data keep working — into a QDockWidget of the panel
/// area named "plot.<panel>.<plot>" (plotKey()). Where the plot was, the panel shows a
/// placeholder ("Fx is shown in its own dock" and a Put back button), so the panel's tabs keep
/// their order and indexes. "Put back into <panel>" or closing the dock returns the plot to its
/// place. While a torn-off plot is on screen, its panel computes even when hidden behind another
/// (AnalysisPanel::setPlotOutside).

#include <QObject>
#include <QPointer>
#include <QStringList>
#include <functional>
#include <memory>
#include <vector>

class QCustomPlot;
class QDockWidget;
class QEvent;
class QMainWindow;
class QSplitter;
class QTabWidget;
class QWidget;

namespace terra::ui {

class AnalysisPanel;

/// The width a dock needs to show its content without a sideways scroll bar [px]: for a dock
/// holding a scroll area (the studio's panels), its content's minimum width plus the vertical
/// scroll bar it may show and the dock's frame.
int dockMinimumWidth(const QDockWidget& dock);

class PlotDocking : public QObject {
    Q_OBJECT
public:
    /// The plots' docks are added to `area` (the studio's panel area).
    explicit PlotDocking(QMainWindow* area, QObject* parent = nullptr);
    ~PlotDocking() override;

    /// Makes the plots of `panel` (AnalysisPanel::plots()) dockable from their right-click menu;
    /// `home` is the dock holding the panel, `title` the panel's title ("Forces vs slip").
    void addPanel(AnalysisPanel* panel, QDockWidget* home, const QString& title);

    /// The dock name of a plot: "plot.<panel>.<key>", the key being the plot's object name when
    /// set (a plot whose plots() name changes with the settings, as the sensitivity's
    /// "sensitivity-K-Fx"), else its plots() name.
    static QString dockName(const AnalysisPanel& panel, const QString& plot_name,
                            const QCustomPlot& plot);

    /// Moves the plot into a dock of its own, beside the panels; the dock (the existing one when
    /// it is torn off already), nullptr for a plot of no added panel.
    QDockWidget* tearOff(QCustomPlot* plot);
    /// The same by dock name; nullptr when no added panel has that plot.
    QDockWidget* tearOff(const QString& dock_name);
    /// Returns the plot to its place in its panel (its tab, at its position) and removes its dock.
    void putBack(QCustomPlot* plot);
    void putAllBack();

    /// The dock of a torn-off plot, nullptr when it is in its panel.
    QDockWidget* dockOf(const QCustomPlot* plot) const;
    /// The torn-off plots' docks, of every panel or of one.
    std::vector<QDockWidget*> docks(const AnalysisPanel* panel = nullptr) const;
    /// The panel whose plot a dock holds (nullptr: not a plot dock).
    AnalysisPanel* panelOf(const QDockWidget* dock) const;
    /// The dock holding a panel (addPanel's `home`).
    QDockWidget* homeOf(const AnalysisPanel* panel) const;
    /// The torn-off plots' dock names, in the order they were torn off (saved with the window).
    QStringList tornOff() const;
    /// Tears off the plots named (tornOff() of an earlier session), so that restoring the window
    /// state finds their docks; a name of no plot (renamed, removed) is ignored. How many were.
    int restore(const QStringList& dock_names);

    /// Runs `f` with the plot's tab (or its placeholder's) current in its panel — the panel's
    /// currentPlot() and currentTable() are then this plot's — and puts the tabs back after.
    void withPlotCurrent(const QCustomPlot* plot, const std::function<void()>& f) const;

signals:
    /// A plot was torn off or put back.
    void changed();

private:
    struct Panel {
        AnalysisPanel* panel;
        QPointer<QDockWidget> home;
        QString title;
    };
    struct Torn {
        const Panel* panel;
        QCustomPlot* plot;
        QPointer<QDockWidget> dock;
        QPointer<QWidget> placeholder;
        QPointer<QTabWidget> tabs;  // the plot was a tab page: its tab's text and tooltip
        QString tab_text;
        QString tab_tooltip;
        QPointer<QSplitter> splitter;  // else in a splitter, else in its parent's layout
    };
    const Panel* panelWith(const QCustomPlot* plot, QString* name = nullptr) const;
    const Torn* tornOf(const QCustomPlot* plot) const;
    QString labelOf(const Panel& panel, const QCustomPlot* plot, const QString& name) const;
    QWidget* placeholderFor(QCustomPlot* plot, const QString& label, const QString& home);
    void place(QDockWidget* dock, const Panel& panel);
    bool eventFilter(QObject* watched, QEvent* event) override;

    QMainWindow* area_;
    std::vector<std::unique_ptr<Panel>> panels_;
    std::vector<Torn> torn_;
};

}  // namespace terra::ui
