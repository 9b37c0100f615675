#include "widgets/plots/plot_readout.h"

#include <qcustomplot.h>

#include <QEvent>
#include <QLabel>
#include <QPointer>
#include <limits>

namespace terra::ui {
namespace {

constexpr const char* kMarkerName = "readout-marker";

bool shown(const QCPAbstractPlottable& p) {
    return p.realVisibility() && p.keyAxis() && p.valueAxis();
}

/// Calls `visit(key, value)` for each data point of a graph, curve or bars inside its axes' ranges.
template <typename Visit>
void eachPoint(const QCPAbstractPlottable& p, Visit&& visit) {
    const QCPRange keys = p.keyAxis()->range(), values = p.valueAxis()->range();
    auto consider = [&](double key, double value) {
        if (keys.contains(key) && values.contains(value)) visit(key, value);
    };
    if (const auto* graph = qobject_cast<const QCPGraph*>(&p)) {
        for (auto it = graph->data()->constBegin(); it != graph->data()->constEnd(); ++it)
            consider(it->key, it->value);
    } else if (const auto* curve = qobject_cast<const QCPCurve*>(&p)) {
        for (auto it = curve->data()->constBegin(); it != curve->data()->constEnd(); ++it)
            consider(it->key, it->value);
    } else if (const auto* bars = qobject_cast<const QCPBars*>(&p)) {
        for (auto it = bars->data()->constBegin(); it != bars->data()->constEnd(); ++it)
            consider(it->key, it->value);  // the end of the bar
    }
}

QPointF pixelOf(const QCPAbstractPlottable& p, double key, double value) {
    const double k = p.keyAxis()->coordToPixel(key), v = p.valueAxis()->coordToPixel(value);
    return p.keyAxis()->orientation() == Qt::Horizontal ? QPointF(k, v) : QPointF(v, k);
}

QString join(const QStringList& parts) {
    QStringList kept;
    for (const QString& part : parts) {
        if (!part.isEmpty()) kept << part;
    }
    return kept.join(",  ");
}

/// The value of the colour map cell under `pixel`, with the colour scale's label.
QString colourMapText(QCustomPlot& plot, const QPointF& pixel) {
    for (int i = 0; i < plot.plottableCount(); ++i) {
        auto* map = qobject_cast<QCPColorMap*>(plot.plottable(i));
        if (!map || !shown(*map)) continue;
        const double key = map->keyAxis()->pixelToCoord(pixel.x());
        const double value = map->valueAxis()->pixelToCoord(pixel.y());
        QCPColorMapData* data = map->data();
        if (!data->keyRange().contains(key) || !data->valueRange().contains(value)) continue;
        const QString scale = map->colorScale() ? map->colorScale()->axis()->label() : QString();
        return join(
            {readoutPart(map->keyAxis()->label(), key),
             readoutPart(map->valueAxis()->label(), value),
             readoutPart(scale.isEmpty() ? QString("value") : scale, data->data(key, value))});
    }
    return {};
}

QCPItemTracer* marker(QCustomPlot& plot) {
    for (int i = 0; i < plot.itemCount(); ++i) {
        if (plot.item(i)->objectName() == kMarkerName)
            return static_cast<QCPItemTracer*>(plot.item(i));
    }
    return nullptr;
}

void removeMarker(QCustomPlot& plot) {
    if (QCPItemTracer* ring = marker(plot)) {
        plot.removeItem(ring);
        plot.replot(QCustomPlot::rpQueuedReplot);
    }
}

/// Clears a read-out and its ring when the plot stops being under the mouse or on screen.
class ReadoutReset : public QObject {
public:
    ReadoutReset(QCustomPlot* plot, QLabel* readout)
        : QObject(plot), plot_(plot), readout_(readout) {}
    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() == QEvent::Leave || event->type() == QEvent::Hide) {
            if (readout_) readout_->clear();
            removeMarker(*plot_);
        }
        return QObject::eventFilter(watched, event);
    }

private:
    QCustomPlot* plot_;
    QPointer<QLabel> readout_;
};

}  // namespace

std::optional<PlotPoint> nearestPoint(QCustomPlot& plot, const QPointF& pixel) {
    std::optional<PlotPoint> best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < plot.plottableCount(); ++i) {
        QCPAbstractPlottable* p = plot.plottable(i);
        if (!shown(*p)) continue;
        eachPoint(*p, [&](double key, double value) {
            const QPointF at = pixelOf(*p, key, value);
            const double distance = QLineF(at, pixel).length();
            if (distance < best_distance) {
                best_distance = distance;
                best = PlotPoint{p, key, value, at};
            }
        });
    }
    return best;
}

QString readoutPart(const QString& label, double value) {
    if (label.isEmpty()) return {};
    const QString name = label.section(" [", 0, 0);
    QString unit = label.section(" [", 1).section(']', 0, 0);
    if (unit == "-") unit.clear();
    return QString("%1 = %2%3")
        .arg(name)
        .arg(value, 0, 'g', 4)
        .arg(unit.isEmpty() ? "" : " " + unit);
}

namespace {

/// A category axis (text ticks: the tornado's parameters, the slips of grouped bars) names the
/// category nearest `key` ("Soil parameter = k_c"), not its position on the axis (0.81).
QString keyPart(const QCPAxis& axis, double key) {
    const auto ticker = axis.ticker().dynamicCast<QCPAxisTickerText>();
    if (!ticker || ticker->ticks().isEmpty()) return readoutPart(axis.label(), key);
    auto nearest = ticker->ticks().constBegin();
    for (auto it = ticker->ticks().constBegin(); it != ticker->ticks().constEnd(); ++it) {
        if (std::abs(it.key() - key) < std::abs(nearest.key() - key)) nearest = it;
    }
    const QString name = axis.label().section(" [", 0, 0);
    const QString category = QString(nearest.value()).replace('\n', ' ');
    // A tick that names itself ("s = 0.1") is shown as is.
    if (name.isEmpty() || category.contains('=')) return category;
    return QString("%1 = %2").arg(name, category);
}

}  // namespace

QString readoutText(QCustomPlot& plot, const QPointF& pixel) {
    const std::optional<PlotPoint> point = nearestPoint(plot, pixel);
    if (!point) return colourMapText(plot, pixel);
    const QCPAbstractPlottable& p = *point->plottable;
    QCPAxis* x = p.keyAxis()->orientation() == Qt::Horizontal ? p.keyAxis() : p.valueAxis();
    QCPAxis* y = x == p.keyAxis() ? p.valueAxis() : p.keyAxis();
    const bool key_is_x = x == p.keyAxis();
    const QString text =
        key_is_x ? join({keyPart(*x, point->key), readoutPart(y->label(), point->value)})
                 : join({readoutPart(x->label(), point->value), keyPart(*y, point->key)});
    return p.name().isEmpty() ? text : text + "  — " + p.name();
}

void installReadout(QCustomPlot& plot, QLabel* label) {
    plot.setMouseTracking(true);
    QCustomPlot* p = &plot;
    QObject::connect(p, &QCustomPlot::mouseMove, label, [p, label](QMouseEvent* event) {
        const QPointF at = event->position();
        label->setText(readoutText(*p, at));
        const std::optional<PlotPoint> point = nearestPoint(*p, at);
        if (!point) {
            removeMarker(*p);
            return;
        }
        QCPItemTracer* ring = marker(*p);
        if (!ring) {
            ring = new QCPItemTracer(p);
            ring->setObjectName(kMarkerName);
            ring->setStyle(QCPItemTracer::tsCircle);
            ring->setSize(10);
            ring->setSelectable(false);
            ring->setPen(QPen(p->palette().color(QPalette::WindowText), 1.5));
        }
        ring->position->setAxes(point->plottable->keyAxis(), point->plottable->valueAxis());
        ring->position->setCoords(point->key, point->value);
        p->replot(QCustomPlot::rpQueuedReplot);
    });
    plot.installEventFilter(new ReadoutReset(p, label));
}

}  // namespace terra::ui
