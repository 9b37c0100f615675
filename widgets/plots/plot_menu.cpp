#include "widgets/plots/plot_menu.h"

#include <qcustomplot.h>

#include <QApplication>
#include <QClipboard>
#include <QMenu>

#include "core/io/csv.h"
#include "widgets/plots/plot_legend.h"

namespace terra::ui {

QMenu* makePlotMenu(QCustomPlot& plot, const PlotMenuHooks& hooks, QWidget* parent,
                    const PlotDockHooks& dock) {
    auto* menu = new QMenu(parent);
    QCustomPlot* p = &plot;
    if (hooks.export_plot) {
        menu->addAction("Export plot…", hooks.export_plot)->setObjectName("plot.export");
    }
    menu->addAction("Copy image", [p] { QApplication::clipboard()->setPixmap(p->toPixmap()); })
        ->setObjectName("plot.copy_image");
    if (hooks.table) {
        menu->addAction(
                "Copy data (CSV)",
                [table = hooks.table] {
                    QApplication::clipboard()->setText(QString::fromStdString(io::toCsv(table())));
                })
            ->setObjectName("plot.copy_data");
    }
    if (dock.in_own_dock && dock.set_own_dock) {
        const bool own = dock.in_own_dock();
        QAction* move = menu->addAction(own ? "Put back into " + dock.home : "Show in its own dock",
                                        [set = dock.set_own_dock, own] { set(!own); });
        move->setObjectName("plot.own_dock");
        move->setToolTip(own ? "Return the plot to its place in the panel"
                             : "Show the plot in a dock of its own beside the panels: drag it "
                               "beside another, float it or tab it");
    }
    menu->addSeparator();
    QAction* legend =
        menu->addAction("Show legend", [p](bool shown) { setLegendShown(*p, shown); });
    legend->setObjectName("plot.legend");
    legend->setCheckable(true);
    legend->setChecked(legendShown(plot));
    legend->setEnabled(p->legend != nullptr);
    QAction* below = menu->addAction("Legend under the plot", [p] { resetLegendPlacement(*p); });
    below->setObjectName("plot.legend_below");
    below->setToolTip(
        "Back to its place under the axes, off the data (drag the legend to move it)");
    below->setEnabled(legendMoved(plot));
    menu->addAction("Reset view",
                    [p] {
                        p->rescaleAxes();
                        p->replot();
                    })
        ->setObjectName("plot.reset_view");
    return menu;
}

void installPlotMenu(QCustomPlot& plot, PlotMenuHooks hooks, PlotDockHooks dock) {
    plot.setContextMenuPolicy(Qt::CustomContextMenu);
    QCustomPlot* p = &plot;
    QObject::connect(p, &QWidget::customContextMenuRequested, p,
                     [p, hooks, dock](const QPoint& at) {
                         QMenu* menu = makePlotMenu(*p, hooks, p, dock);
                         menu->setAttribute(Qt::WA_DeleteOnClose);
                         menu->popup(p->mapToGlobal(at));
                     });
}

}  // namespace terra::ui
