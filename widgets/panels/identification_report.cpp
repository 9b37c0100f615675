#include "widgets/panels/identification_report.h"

#include <QStringList>
#include <QTableWidget>
#include <cmath>

#include "widgets/panels/data_preview.h"
#include "widgets/plots/number_format.h"

namespace terra::ui {
namespace {

QString number(double value, int digits = 4) { return QString::number(value, 'g', digits); }

/// The size of a field's values: what rounding noise is measured against (formatNumber).
double scaleOf(const FieldInfo& field) {
    const double high = std::max(std::abs(field.range.low), std::abs(field.range.high));
    return std::isfinite(high) ? high : 1.0;
}

}  // namespace

void fillParameterTable(QTableWidget& table, const analysis::IdentificationResult& result,
                        const std::optional<identification::DecoupledParameters>& truth) {
    const Table& t = result.parameters;
    const bool synthetic = truth.has_value();
    const identification::IdentificationReport* report = result.report ? &*result.report : nullptr;
    const auto fields = analysis::identifiedFields();
    table.setRowCount(static_cast<int>(fields.size()));
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const analysis::IdentifiedField& field = fields[i];
        const int row = static_cast<int>(i);
        auto* name = new QTableWidgetItem(QString::fromStdString(field.symbolWithUnit()));
        name->setToolTip(QString::fromUtf8(field.description));
        table.setItem(row, 0, name);
        // The value to the digits its std supports; without one, to 5 digits with rounding
        // noise as 0 (a c at its bound of 0 read "-1.25e-18").
        double sd = 0.0;
        for (std::size_t c = fields.size(); c < t.columns.size(); ++c) {
            if (t.columns[c] == std::string(field.key) + "_std") sd = t.rows[0][c];
        }
        const double value = t.rows[0][i];
        table.setItem(row, 1,
                      new QTableWidgetItem(std::isinf(value) ? QString("none")  // j_max: no limit
                                           : sd > 0.0        ? formatWithStd(value, sd)
                                                      : formatNumber(value, scaleOf(field), 5)));
        table.setItem(row, 2, new QTableWidgetItem(formatStd(sd)));
        QString prior = "–", ratio = "–";
        if (const auto full = analysis::fullParameterOf(field); report && full) {
            const identification::PriorComparison& c =
                report->prior[static_cast<std::size_t>(*full)];
            if (c.active) {
                // As the user gave it ("12 ± 2"), rounding noise of the unit conversion dropped.
                prior = formatNumber(c.prior_mean / field.to_si, scaleOf(field)) + " ± " +
                        formatNumber(c.prior_std / field.to_si);
                ratio = QString::number(c.std_ratio, 'f', 2);
            }
        }
        table.setItem(row, 3, new QTableWidgetItem(prior));
        table.setItem(row, 4, new QTableWidgetItem(ratio));
        table.setItem(
            row, 5,
            new QTableWidgetItem(!synthetic ? QString("–")
                                 : std::isinf(field.userValue(*truth))
                                     ? QString("none")
                                     : formatNumber(field.userValue(*truth), scaleOf(field), 5)));
    }
}

QString identificationReport(const analysis::IdentificationResult& result) {
    const identification::IdentificationReport* report = result.report ? &*result.report : nullptr;
    QStringList lines;
    lines << QString::fromStdString(result.start_description).toHtmlEscaped();
    if (report) {
        lines << QString("Data: %1.")
                     .arg(withChannelSymbols(QString::fromStdString(report->setup.description)));
        // The Newton decrement gᵀH⁻¹g in a user's words: what one more step would still gain in
        // χ², against the change of 1 that is one σ (the gradient norm stays in the JSON
        // report).
        if (report->newton_decrement < 0.1)
            lines << QString(
                "At a minimum: one more step would lower χ² by less than 0.1 (a "
                "change of 1 is one σ).");
        else
            lines << QString(
                         "Not clearly at a minimum: one more step would still lower χ² by "
                         "%1 (a change of 1 is one σ); fit again, or fix or give priors to "
                         "the parameters the data do not determine.")
                         .arg(number(report->newton_decrement, 2));
        if (report->holdout.computed) {
            QStringList channels;
            for (int c = 0; c < identification::kChannelCount; ++c) {
                const auto k = static_cast<std::size_t>(c);
                if (!report->holdout.channels[k]) continue;
                channels << QString("%1 %2 (%3 σ)")
                                .arg(withChannelSymbols(identification::channelNames()[k]))
                                .arg(number(report->holdout.rms[k], 3))
                                .arg(QString::number(report->holdout.rms_over_noise[k], 'f', 2));
            }
            lines << QString(
                         "Held-out RMS (%1 samples, %2 fold(s)): %3. ≈ 1 σ: the model "
                         "predicts new samples to the noise.")
                         .arg(report->holdout.samples)
                         .arg(report->holdout.folds)
                         .arg(channels.join(", "));
        } else {
            lines << QString("Held-out error: not computed (choose hold out or 5-fold).");
        }
        auto answer = [](const identification::ParameterVector& p) {
            QStringList values;
            for (const char* key : {"phi_deg", "c_kPa", "Ks_kPa", "n0", "K_m"}) {
                const analysis::IdentifiedField& f = *analysis::findIdentifiedField(key);
                const auto full = analysis::fullParameterOf(f);
                values << QString("%1 = %2")
                              .arg(QString::fromUtf8(f.symbol))
                              .arg(formatNumber(p[static_cast<std::size_t>(*full)] / f.to_si,
                                                scaleOf(f)));
            }
            return values.join(", ");
        };
        if (report->ambiguity.empty()) {
            lines << QString("Ambiguity: none (no other minimum within Δχ² = %1).")
                         .arg(number(report->ambiguity_delta_chi2, 3));
        } else {
            lines << QString(
                         "<b>Ambiguous</b>: %1 other minimum(s) within Δχ² = %2 — the data "
                         "cannot choose. Best: %3.")
                         .arg(report->ambiguity.size())
                         .arg(number(report->ambiguity_delta_chi2, 3))
                         .arg(answer(report->parameters));
            for (const identification::Minimum& m : report->ambiguity) {
                lines << QString("Other (Δχ² = %1): %2.")
                             .arg(number(m.delta_chi2, 3))
                             .arg(answer(m.parameters));
            }
        }
        if (report->adequacy.flag) {
            lines << QString(
                         "<b>Systematic misfit</b> (adequacy p = %1): the residuals follow "
                         "slip, so "
                         "the estimate is biased and its std too small (the note below says "
                         "where; a shear limit? try j_max: fit).")
                         .arg(number(report->adequacy.p, 2));
        } else {
            lines << QString("Adequacy: the residuals look like noise (smallest p = %1).")
                         .arg(number(report->adequacy.p, 2));
        }
        for (const auto& flag : report->uncertainty.flags)
            lines << QString::fromStdString(flag).toHtmlEscaped();
    }
    return lines.join("<br>");
}

QString identificationSteps(const analysis::IdentificationResult& result) {
    QStringList steps;
    for (const auto& step : result.steps()) {
        steps << QString("%1: Σr² = %2")
                     .arg(QString::fromStdString(step.name))
                     .arg(step.squared_residual_norm, 0, 'g', 4);
    }
    return QString("Fit in %1 ms. ").arg(result.fit_time_ms, 0, 'f', 0) + steps.join(";  ");
}

}  // namespace terra::ui
