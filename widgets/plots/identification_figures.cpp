#include "widgets/plots/identification_figures.h"

#include <qcustomplot.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "core/analysis/identified_parameters.h"

namespace terra::ui {
namespace {

const QColor kBlue(31, 119, 180), kOrange(255, 127, 14), kGreen(44, 160, 44),
    kPurple(148, 103, 189), kBrown(140, 86, 75), kRed(214, 39, 40), kGrey(110, 110, 110);

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const QString kBandSuffix = " ±σ";

// The estimates drawn, by graph name, and the field of the identified parameters each shows.
constexpr std::pair<const char*, const char*> kPlotted[] = {
    {"phi", "phi_deg"}, {"c", "c_kPa"}, {"Ks", "Ks_kPa"}, {"n0", "n0"}, {"K", "K_m"}};

// "φ [deg]": the axis label of an identified parameter (identified_parameters.h).
QString label(const char* key) {
    return QString::fromStdString(analysis::findIdentifiedField(key)->symbolWithUnit());
}

void styleAxisLabel(QCPAxis* axis, const QString& label, const QColor& color) {
    axis->setLabel(label);
    axis->setLabelColor(color);
    axis->setTickLabelColor(color);
    axis->setBasePen(QPen(color));
    axis->setTickPen(QPen(color));
    axis->setSubTickPen(QPen(color));
}

QCPGraph* lineGraph(QCPAxis* key, QCPAxis* value, const QColor& color, const QString& name) {
    auto* g = key->parentPlot()->addGraph(key, value);
    g->setPen(QPen(color, 1.6));
    g->setName(name);
    return g;
}

QCPGraph* dotGraph(QCPAxis* key, QCPAxis* value, const QColor& color,
                   QCPScatterStyle::ScatterShape shape, double size, const QString& name) {
    auto* g = key->parentPlot()->addGraph(key, value);
    g->setLineStyle(QCPGraph::lsNone);
    g->setScatterStyle(QCPScatterStyle(shape, color, size));
    g->setPen(QPen(color));
    g->setName(name);
    return g;
}

// Both value axes of a rect fitted to their graphs' finite values, with a margin.
void rescaleValues(QCPAxisRect* rect) {
    for (QCPAxis* axis : {rect->axis(QCPAxis::atLeft), rect->axis(QCPAxis::atRight)}) {
        bool found = false;
        QCPRange range;
        for (QCPGraph* g : axis->graphs()) {
            // The ±σ bands may be wide right after a (re)initialisation: the axes follow the
            // estimates, the bands are clipped.
            if (!g->visible() || g->dataCount() == 0 || g->name().endsWith(kBandSuffix)) continue;
            bool ok = false;
            const QCPRange r = g->getValueRange(ok, QCP::sdBoth);
            if (!ok || !std::isfinite(r.lower) || !std::isfinite(r.upper)) continue;
            if (!found)
                range = r;
            else
                range.expand(r);
            found = true;
        }
        if (!found) continue;
        if (axis->scaleType() == QCPAxis::stLogarithmic) {
            axis->setRange(std::min(range.lower, 1.0) / 2.0, std::max(range.upper, 10.0) * 2.0);
        } else {
            const double pad = range.size() > 0.0 ? 0.08 * range.size()
                                                  : std::max(1e-6, 0.05 * std::abs(range.lower));
            axis->setRange(range.lower - pad, range.upper + pad);
        }
    }
}

}  // namespace

StreamingFigures::StreamingFigures(QCustomPlot* estimates, QCustomPlot* detection)
    : estimates_(estimates), detection_(detection) {
    for (QCustomPlot* plot : {estimates_, detection_}) {
        plot->clearPlottables();
        plot->clearItems();
        plot->plotLayout()->clear();  // also drops the default axis rect (xAxis/yAxis become null)
        plot->plotLayout()->setRowSpacing(0);
    }
    auto* est_margins = new QCPMarginGroup(estimates_);
    auto* det_margins = new QCPMarginGroup(detection_);
    // Estimates: φ | c, K_s | n₀, K.
    QCPAxisRect* r0 = addRect(estimates_, 1, label("phi_deg"), label("c_kPa"), false);
    QCPAxisRect* r1 = addRect(estimates_, 2, label("Ks_kPa"), label("n0"), false);
    QCPAxisRect* r2 = addRect(estimates_, 3, label("K_m"), "", false);
    // Detection: score, F_x.
    QCPAxisRect* r3 = addRect(detection_, 1, "CUSUM g [-]", "", false);
    QCPAxisRect* r4 = addRect(detection_, 2, "F_x [N]", "", false);
    for (QCPAxisRect* r : {r0, r1, r2}) r->setMarginGroup(QCP::msLeft | QCP::msRight, est_margins);
    for (QCPAxisRect* r : {r3, r4}) r->setMarginGroup(QCP::msLeft | QCP::msRight, det_margins);
    r2->axis(QCPAxis::atBottom)->setLabel("Sample");
    r4->axis(QCPAxis::atBottom)->setLabel("Sample");

    auto left = [](QCPAxisRect* r) { return r->axis(QCPAxis::atLeft); };
    auto right = [](QCPAxisRect* r) { return r->axis(QCPAxis::atRight); };
    auto bottom = [](QCPAxisRect* r) { return r->axis(QCPAxis::atBottom); };
    graphs_ = {
        {"phi", lineGraph(bottom(r0), left(r0), kBlue, "φ")},
        {"c", lineGraph(bottom(r0), right(r0), kOrange, "c")},
        {"Ks", lineGraph(bottom(r1), left(r1), kGreen, "K_s")},
        {"n0", lineGraph(bottom(r1), right(r1), kPurple, "n₀")},
        {"K", lineGraph(bottom(r2), left(r2), kBrown, "K")},
        {"score", lineGraph(bottom(r3), left(r3), kBlue, "CUSUM")},
        {"far_off",
         dotGraph(bottom(r3), left(r3), kRed, QCPScatterStyle::ssDisc, 5.0, "above threshold")},
        {"fx_measured", dotGraph(bottom(r4), left(r4), QColor(40, 40, 40), QCPScatterStyle::ssDisc,
                                 3.5, "measured")},
        {"fx_predicted",
         dotGraph(bottom(r4), left(r4), kOrange, QCPScatterStyle::ssCross, 5.0, "predicted")},
    };
    // The truth of synthetic data: dotted, same colours, same axes.
    const std::vector<std::tuple<QString, QCPAxis*, QCPAxis*, QColor>> truth{
        {"phi_true", bottom(r0), left(r0), kBlue},
        {"c_true", bottom(r0), right(r0), kOrange},
        {"Ks_true", bottom(r1), left(r1), kGreen},
        {"n0_true", bottom(r1), right(r1), kPurple},
        {"K_true", bottom(r2), left(r2), kBrown}};
    for (const auto& [name, key, value, color] : truth) {
        QCPGraph* g = lineGraph(key, value, color, name);
        g->setPen(QPen(color, 1.2, Qt::DotLine));
        graphs_.emplace_back(name, g);
        // The estimate ± its std (the estimator's posterior), a shaded band under the line.
        const QString base = name.left(name.size() - 5);  // "phi_true" → "phi"
        QCPGraph* lo = lineGraph(key, value, color, base + "_lo" + kBandSuffix);
        QCPGraph* hi = lineGraph(key, value, color, base + "_hi" + kBandSuffix);
        QColor edge = color;
        edge.setAlpha(90);
        QColor fill = color;
        fill.setAlpha(45);
        for (QCPGraph* b : {lo, hi}) {
            b->setPen(QPen(edge, 0.8));
            b->setLayer("grid");  // below the estimates (layer "main")
        }
        hi->setBrush(fill);
        hi->setChannelFillGraph(lo);
        graphs_.emplace_back(base + "_lo", lo);
        graphs_.emplace_back(base + "_hi", hi);
    }
    styleAxisLabel(left(r0), label("phi_deg"), kBlue);
    styleAxisLabel(right(r0), label("c_kPa"), kOrange);
    styleAxisLabel(left(r1), label("Ks_kPa"), kGreen);
    styleAxisLabel(right(r1), label("n0"), kPurple);
    styleAxisLabel(left(r2), label("K_m"), kBrown);
    current_ =
        dotGraph(bottom(r4), left(r4), kRed, QCPScatterStyle::ssCircle, 12.0, "current sample");
    current_->setPen(QPen(kRed, 2.0));

    for (auto& [name, g] : graphs_) g->removeFromLegend();
    current_->removeFromLegend();

    // Titles.
    estimates_->plotLayout()->addElement(
        0, 0, new QCPTextElement(estimates_, "Estimates", QFont("sans", 10, QFont::Bold)));
    detection_->plotLayout()->addElement(
        0, 0, new QCPTextElement(detection_, "Change detection", QFont("sans", 10, QFont::Bold)));
    // The current sample's F_x, above its rect (inside it would cover data).
    detection_->plotLayout()->insertRow(2);
    current_label_ = new QCPTextElement(detection_, "", QFont("sans", 9));
    // Two short lines, and never the plot's minimum width: one line of it widened the streaming
    // page past a 1024×700 screen (less openbox's frame) once a sample was shown.
    current_label_->setMinimumSize(1, 0);
    detection_->plotLayout()->addElement(2, 0, current_label_);

    // One sample axis: dragging or zooming one rect moves all of a figure's rects.
    for (QCustomPlot* plot : {estimates_, detection_}) {
        const auto rects = plot->axisRects();
        for (QCPAxisRect* a : rects) {
            a->setRangeDrag(Qt::Horizontal);
            a->setRangeZoom(Qt::Horizontal);
            for (QCPAxisRect* b : rects) {
                if (a == b) continue;
                QObject::connect(
                    a->axis(QCPAxis::atBottom), qOverload<const QCPRange&>(&QCPAxis::rangeChanged),
                    b->axis(QCPAxis::atBottom), qOverload<const QCPRange&>(&QCPAxis::setRange));
            }
        }
        plot->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
    }
    reset("Estimates", 0, std::nullopt,
          identification::StreamingEstimatorOptions{}.change_threshold);
}

QCPAxisRect* StreamingFigures::addRect(QCustomPlot* plot, int row, const QString& left,
                                       const QString& right, bool log) {
    auto* rect = new QCPAxisRect(plot);
    plot->plotLayout()->addElement(row, 0, rect);
    rect->setupFullAxesBox(false);
    rect->axis(QCPAxis::atTop)->setVisible(false);
    rect->axis(QCPAxis::atBottom)->grid()->setZeroLinePen(Qt::NoPen);
    rect->axis(QCPAxis::atLeft)->setLabel(left);
    QCPAxis* r = rect->axis(QCPAxis::atRight);
    r->setVisible(!right.isEmpty());
    r->setTickLabels(!right.isEmpty());
    r->setLabel(right);
    if (log) {
        QCPAxis* l = rect->axis(QCPAxis::atLeft);
        l->setScaleType(QCPAxis::stLogarithmic);
        l->setTicker(QSharedPointer<QCPAxisTickerLog>(new QCPAxisTickerLog));
    }
    rect->setMinimumSize(100, 70);
    rects_.push_back(rect);
    return rect;
}

QCPGraph* StreamingFigures::graph(const QString& name) const {
    for (const auto& [n, g] : graphs_) {
        if (n == name) return g;
    }
    return name == "current" ? current_ : nullptr;
}

void StreamingFigures::setCompletion(Completion completion) {
    if (auto* t = qobject_cast<QCPTextElement*>(estimates_->plotLayout()->element(0, 0)))
        t->setText(markedTitle(title_, completion));
}

QString StreamingFigures::title() const {
    const auto* t = qobject_cast<QCPTextElement*>(estimates_->plotLayout()->element(0, 0));
    return t ? t->text() : QString();
}

void StreamingFigures::reset(const QString& title, std::size_t sample_count,
                             std::optional<std::size_t> true_border, double threshold) {
    for (auto& [name, g] : graphs_) g->data()->clear();
    current_->data()->clear();
    estimates_->clearItems();
    detection_->clearItems();
    frames_ = 0;
    sample_count_ = sample_count;
    threshold_ = threshold;
    changes_.clear();
    confirmed_.clear();
    title_ = title;
    setCompletion(Completion::kComplete);
    const double upper = std::max<double>(10.0, static_cast<double>(sample_count));
    for (QCPAxisRect* r : rects_)
        r->axis(QCPAxis::atBottom)->setRange(-0.02 * upper - 0.5, 1.02 * upper + 0.5);
    // The CUSUM's threshold h (streaming_estimator.h): above it an alarm, which the
    // likelihood-ratio test then confirms or rejects.
    QCPAxisRect* score = rects_[3];
    auto* line = new QCPItemStraightLine(detection_);
    line->setClipAxisRect(score);
    for (auto* p : {line->point1, line->point2})
        p->setAxes(score->axis(QCPAxis::atBottom), score->axis(QCPAxis::atLeft));
    line->point1->setCoords(0.0, threshold);
    line->point2->setCoords(1.0, threshold);
    line->setPen(QPen(kRed, 1.0, Qt::DashLine));
    auto* label = new QCPItemText(detection_);
    label->setClipAxisRect(score);
    label->setClipToAxisRect(true);
    label->position->setAxes(score->axis(QCPAxis::atBottom), score->axis(QCPAxis::atLeft));
    label->position->setTypeX(QCPItemPosition::ptAxisRectRatio);
    label->position->setAxisRect(score);
    label->position->setCoords(0.01, threshold);
    label->setPositionAlignment(Qt::AlignLeft | Qt::AlignBottom);
    label->setText(QString("threshold %1").arg(threshold, 0, 'g', 3));  // 13.8, not 13.8155
    label->setColor(kRed);
    label->setFont(QFont("sans", 8));
    border_ = true_border;
    border_labels_.clear();
    if (true_border)
        border_labels_ = markVertical(*true_border, kGrey, Qt::DashLine, "true border");
    current_label_->setText(
        "F_x at the current sample (○):\nmeasured (●), predicted by the estimate before it (×)");
}

void StreamingFigures::setTruth(
    const std::vector<std::pair<std::size_t, identification::DecoupledParameters>>& truth) {
    for (const char* name : {"phi_true", "c_true", "Ks_true", "n0_true", "K_true"})
        graph(name)->data()->clear();
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const double from = static_cast<double>(truth[i].first) - 0.5;
        const double to = (i + 1 < truth.size() ? static_cast<double>(truth[i + 1].first)
                                                : static_cast<double>(sample_count_)) -
                          0.5;
        const auto& p = truth[i].second;
        for (const auto& [name, key] : kPlotted) {
            const double v = analysis::findIdentifiedField(key)->userValue(p);
            QCPGraph* g = graph(QString(name) + "_true");
            if (i > 0) g->addData(from, kNaN);  // a step, not a slope, at the border
            g->addData(from + 1e-9, v);
            g->addData(to - 1e-9, v);
        }
    }
}

std::vector<QCPItemText*> StreamingFigures::markVertical(std::size_t index, const QColor& color,
                                                         Qt::PenStyle style, const QString& label,
                                                         const QString& long_label) {
    std::vector<QCPItemText*> labels;
    const double x =
        static_cast<double>(index) - 0.5;  // between the last old and the first new sample
    for (std::size_t i = 0; i < rects_.size(); ++i) {
        QCPAxisRect* r = rects_[i];
        QCustomPlot* plot = r->parentPlot();
        auto* line = new QCPItemStraightLine(plot);
        line->setClipAxisRect(r);
        for (auto* p : {line->point1, line->point2})
            p->setAxes(r->axis(QCPAxis::atBottom), r->axis(QCPAxis::atLeft));
        line->point1->setCoords(x, 1.0);
        line->point2->setCoords(x, 2.0);
        line->setPen(QPen(color, 1.5, style));
        if (i == 0 || i == 3) {  // label once per figure, at the top
            auto* text = new QCPItemText(plot);
            text->setClipAxisRect(r);
            text->position->setAxes(r->axis(QCPAxis::atBottom), r->axis(QCPAxis::atLeft));
            text->position->setTypeY(QCPItemPosition::ptAxisRectRatio);
            text->position->setAxisRect(r);
            text->position->setCoords(x, 0.02);
            text->setPositionAlignment(style == Qt::SolidLine ? (Qt::AlignLeft | Qt::AlignTop)
                                                              : (Qt::AlignRight | Qt::AlignTop));
            text->setPadding(QMargins(3, 0, 3, 0));
            text->setText(i == 3 && !long_label.isEmpty() ? long_label : label);
            text->setColor(color);
            text->setFont(QFont("sans", 8));
            labels.push_back(text);
        }
    }
    return labels;
}

void StreamingFigures::append(const std::vector<StreamFrame>& frames) {
    auto g = [this](const char* name) { return graph(name); };
    for (const StreamFrame& f : frames) {
        const auto& u = f.estimate;
        const double k = static_cast<double>(u.index);
        for (const auto& [name, key] : kPlotted) {
            const analysis::IdentifiedField& field = *analysis::findIdentifiedField(key);
            const double v = field.userValue(f.parameters);
            g(name)->addData(k, u.estimated ? v : kNaN);
            const auto full = analysis::fullParameterOf(field);
            const double sd =
                u.estimated && full ? u.std[static_cast<std::size_t>(*full)] / field.to_si : kNaN;
            g((QString(name) + "_lo").toUtf8().constData())->addData(k, v - sd);
            g((QString(name) + "_hi").toUtf8().constData())->addData(k, v + sd);
        }
        g("score")->addData(k, u.estimated || u.cusum > 0.0 ? u.cusum : kNaN);
        if (u.cusum > threshold_) g("far_off")->addData(k, u.cusum);
        g("fx_measured")->addData(k, f.fx_measured_n);
        g("fx_predicted")->addData(k, f.fx_predicted_n);
        if (u.change_detected && u.change_at) {
            changes_.push_back(*u.change_at);
            markVertical(*u.change_at, kRed, Qt::SolidLine,
                         QString("change at %1").arg(*u.change_at),
                         QString("change at %1\n(confirmed at %2)").arg(*u.change_at).arg(u.index));
            confirmed_.push_back(u.index);
            // A change found within a tenth of the run of the true border: its label at the top
            // would run into the border's, which moves to mid-height on a light background.
            const double near = 0.1 * static_cast<double>(std::max<std::size_t>(sample_count_, 10));
            if (border_ && std::abs(static_cast<double>(*u.change_at) -
                                    static_cast<double>(*border_)) < near) {
                for (QCPItemText* text : border_labels_) {
                    text->position->setCoords(text->position->coords().x(), 0.5);
                    text->setPositionAlignment(Qt::AlignRight | Qt::AlignVCenter);
                    text->setBrush(QColor(255, 255, 255, 210));
                }
            }
        }
        ++frames_;
    }
    if (!frames.empty()) {
        const StreamFrame& f = frames.back();
        current_->data()->clear();
        current_->addData(static_cast<double>(f.estimate.index), f.fx_measured_n);
        current_label_->setText(
            std::isfinite(f.fx_predicted_n)
                ? QString("F_x at sample %1 (t = %2 s, ○):\nmeasured %3 N (●), predicted %4 N (×)")
                      .arg(f.estimate.index)
                      .arg(f.time_s, 0, 'f', 2)
                      .arg(f.fx_measured_n, 0, 'f', 2)
                      .arg(f.fx_predicted_n, 0, 'f', 2)
                : QString("F_x at sample %1 (t = %2 s, ○):\nmeasured %3 N (●), no estimate yet")
                      .arg(f.estimate.index)
                      .arg(f.time_s, 0, 'f', 2)
                      .arg(f.fx_measured_n, 0, 'f', 2));
    }
}

void StreamingFigures::replot() {
    for (QCPAxisRect* r : rects_) rescaleValues(r);
    estimates_->replot(QCustomPlot::rpQueuedReplot);
    detection_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace terra::ui
