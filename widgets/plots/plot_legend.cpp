#include "widgets/plots/plot_legend.h"

#include <qcustomplot.h>

#include <QMouseEvent>
#include <algorithm>

namespace terra::ui {
namespace {

// The user's choice, kept on the plot widget (figures redraw the plot, never the widget).
constexpr const char* kHiddenProperty = "terra_legend_hidden";
constexpr const char* kPlaceProperty = "terra_legend_place";  // QPointF: fractions of the axes
constexpr const char* kDragName = "terra_legend_drag";
constexpr const char* kColumnsProperty = "terra_legend_columns";  // int: a figure's maximum

/// Room left and right of a legend under the axes [px]: the legend's own margins and a border.
constexpr int kLegendSideRoom = 16;

bool usable(const QCustomPlot& plot) { return plot.legend && plot.axisRectCount() > 0; }

constexpr const char* kRowName = "terra_legend_row";  // the row under the axes holding a legend

bool inInset(const QCustomPlot& plot) {
    return plot.legend->layout() == plot.axisRect()->insetLayout();
}

/// The row under the axes that holds the legend, or null when the legend is elsewhere.
QCPLayoutGrid* rowOf(const QCustomPlot& plot) {
    auto* row = qobject_cast<QCPLayoutGrid*>(plot.legend->layout());
    return row && row->objectName() == kRowName ? row : nullptr;
}

/// Drops the rows under the axes that no longer hold the legend (a figure's resetPlot() takes the
/// legend out of its row).
void dropEmptyRows(QCustomPlot& plot) {
    QCPLayoutGrid* grid = plot.plotLayout();
    bool dropped = false;
    for (int i = grid->elementCount() - 1; i >= 0; --i) {
        auto* row = qobject_cast<QCPLayoutGrid*>(grid->elementAt(i));
        if (!row || row->objectName() != kRowName || plot.legend->layout() == row) continue;
        grid->removeAt(i);
        dropped = true;
    }
    if (dropped) grid->simplify();
}

/// Takes the legend out of its layout (and drops the row it leaves).
void takeLegend(QCustomPlot& plot) {
    if (plot.legend->layout()) plot.legend->layout()->take(plot.legend);
    dropEmptyRows(plot);
    plot.plotLayout()->simplify();
}

/// Entries a row that fit `width_px`: each column as wide as the widest entry.
int fittingColumns(const QCPLegend& legend, int width_px) {
    int widest = 1;
    int entries = 0;
    for (int i = 0; i < legend.elementCount(); ++i) {
        const QCPLayoutElement* item = legend.elementAt(i);  // a cell may be empty
        if (!item) continue;
        widest = std::max(widest, item->minimumOuterSizeHint().width());
        ++entries;
    }
    const int spacing = legend.columnSpacing();
    const int room =
        width_px - kLegendSideRoom - legend.margins().left() - legend.margins().right();
    const int columns = (room + spacing) / (widest + spacing);
    return std::clamp(columns, 1, std::max(1, entries));
}

/// Under the axes, centred: a row of [space, legend, space] whose legend column is only as wide as
/// the legend's entries (alone in the plot's column, it was stretched to the axes' width with
/// its entries spread out).
void placeBelow(QCustomPlot& plot, int width_px) {
    QCPLegend* legend = plot.legend;
    const bool below = rowOf(plot) != nullptr;
    if (!below) {
        takeLegend(plot);
        QCPLayoutGrid* grid = plot.plotLayout();
        auto* row = new QCPLayoutGrid;
        row->setObjectName(kRowName);
        const int index = grid->rowCount();
        grid->addElement(index, 0, row);
        grid->setRowStretchFactor(index, 0.001);
        row->addElement(0, 0, new QCPLayoutElement(&plot));
        row->addElement(0, 1, legend);
        row->addElement(0, 2, new QCPLayoutElement(&plot));
        row->setColumnSpacing(0);
        row->setAutoMargins(QCP::msNone);
        row->setMargins(QMargins(0, 0, 0, 4));  // off the plot's lower edge
        legend->setMargins(QMargins(6, 2, 6, 2));
    }
    const int most = plot.property(kColumnsProperty).toInt();
    const int fitting = fittingColumns(*legend, width_px);
    const int columns = most > 0 ? std::min(most, fitting) : fitting;
    if (!below || legend->wrap() != columns ||
        legend->fillOrder() != QCPLayoutGrid::foColumnsFirst) {
        legend->setWrap(columns);
        legend->setFillOrder(QCPLayoutGrid::foColumnsFirst);  // rearranges the entries
    }
    legend->setSizeConstraintRect(QCPLayoutElement::scrOuterRect);
    legend->setMaximumSize(legend->minimumOuterSizeHint());
}

void placeInside(QCustomPlot& plot, const QPointF& place) {
    QCPLegend* legend = plot.legend;
    QCPLayoutInset* inset = plot.axisRect()->insetLayout();
    if (!inInset(plot)) {
        takeLegend(plot);
        inset->addElement(legend, Qt::AlignRight | Qt::AlignTop);
        legend->setWrap(0);
        legend->setFillOrder(QCPLayoutGrid::foRowsFirst);
        legend->setMargins(QMargins(7, 5, 7, 4));
        legend->setMaximumSize(QWIDGETSIZE_MAX, QWIDGETSIZE_MAX);
    }
    for (int i = 0; i < inset->elementCount(); ++i) {
        if (inset->elementAt(i) != legend) continue;
        inset->setInsetPlacement(i, QCPLayoutInset::ipFree);
        inset->setInsetRect(i, QRectF(place, QSizeF(0, 0)));  // the legend's own size
    }
}

/// Drags a legend with the left button; consumes the events so that the axes do not pan.
class LegendDrag : public QObject {
public:
    explicit LegendDrag(QCustomPlot* plot) : QObject(plot), plot_(plot) {}

    bool eventFilter(QObject*, QEvent* event) override {
        if (!usable(*plot_)) return false;
        const QCPLegend* legend = plot_->legend;
        switch (event->type()) {
            case QEvent::MouseButtonPress: {
                auto* e = static_cast<QMouseEvent*>(event);
                if (e->button() != Qt::LeftButton || !legend->realVisibility() ||
                    !legend->outerRect().contains(e->position().toPoint()))
                    return false;
                grab_ = e->position() - QPointF(legend->outerRect().topLeft());
                dragging_ = true;
                plot_->setCursor(Qt::ClosedHandCursor);
                return true;
            }
            case QEvent::MouseMove: {
                auto* e = static_cast<QMouseEvent*>(event);
                if (!dragging_) {
                    const bool over = legend->realVisibility() &&
                                      legend->outerRect().contains(e->position().toPoint());
                    over ? plot_->setCursor(Qt::OpenHandCursor) : plot_->unsetCursor();
                    return false;
                }
                moveLegend(*plot_, e->position() - grab_);
                plot_->replot(QCustomPlot::rpQueuedReplot);
                return true;
            }
            case QEvent::MouseButtonRelease:
            case QEvent::MouseButtonDblClick:
                if (!dragging_) return false;
                dragging_ = false;
                plot_->unsetCursor();
                return true;
            default:
                return false;
        }
    }

private:
    QCustomPlot* plot_;
    QPointF grab_;  // where the legend was taken, from its top-left corner [px]
    bool dragging_ = false;
};

}  // namespace

void layOutLegend(QCustomPlot& plot, int width_px) {
    if (!usable(plot)) return;
    if (!legendShown(plot)) plot.legend->setVisible(false);
    dropEmptyRows(plot);
    if (!plot.legend->visible()) {
        // A hidden legend under the axes would still take its row: it waits in the axes' inset.
        if (!inInset(plot)) {
            takeLegend(plot);
            plot.axisRect()->insetLayout()->addElement(plot.legend, Qt::AlignRight | Qt::AlignTop);
            plot.legend->setMaximumSize(QWIDGETSIZE_MAX, QWIDGETSIZE_MAX);
        }
        return;
    }
    const QVariant place = plot.property(kPlaceProperty);
    if (place.isValid()) {
        placeInside(plot, place.toPointF());
    } else {
        placeBelow(plot, width_px > 0 ? width_px : plot.width());
    }
}

void setLegendColumns(QCustomPlot& plot, int columns) {
    plot.setProperty(kColumnsProperty, columns > 0 ? QVariant(columns) : QVariant());
}

void setLegendShown(QCustomPlot& plot, bool shown) {
    plot.setProperty(kHiddenProperty, shown ? QVariant() : QVariant(true));
    if (plot.legend) plot.legend->setVisible(shown && plot.legend->itemCount() > 0);
    plot.replot(QCustomPlot::rpQueuedReplot);
}

bool legendShown(const QCustomPlot& plot) { return !plot.property(kHiddenProperty).isValid(); }

void moveLegend(QCustomPlot& plot, const QPointF& top_left) {
    if (!usable(plot)) return;
    // The inset layout's rect: the axes less its margins, what the fractions are of.
    const QRect axes = plot.axisRect()->insetLayout()->rect();
    const QSize size = plot.legend->outerRect().size();
    if (axes.width() <= 0 || axes.height() <= 0) return;
    // Inside the axes, whole: a legend dropped past an edge stops at it.
    const double x = std::clamp((top_left.x() - axes.left()) / axes.width(), 0.0,
                                std::max(0.0, 1.0 - double(size.width()) / axes.width()));
    const double y = std::clamp((top_left.y() - axes.top()) / axes.height(), 0.0,
                                std::max(0.0, 1.0 - double(size.height()) / axes.height()));
    plot.setProperty(kPlaceProperty, QPointF(x, y));
    placeInside(plot, QPointF(x, y));
}

bool legendMoved(const QCustomPlot& plot) { return plot.property(kPlaceProperty).isValid(); }

void resetLegendPlacement(QCustomPlot& plot) {
    plot.setProperty(kPlaceProperty, QVariant());
    layOutLegend(plot);
    plot.replot(QCustomPlot::rpQueuedReplot);
}

void installLegendControls(QCustomPlot& plot) {
    if (plot.findChild<QObject*>(kDragName, Qt::FindDirectChildrenOnly)) return;  // installed
    auto* drag = new LegendDrag(&plot);
    drag->setObjectName(kDragName);
    plot.installEventFilter(drag);
    QCustomPlot* p = &plot;
    QObject::connect(p, &QCustomPlot::beforeReplot, p, [p] { layOutLegend(*p); });
}

}  // namespace terra::ui
