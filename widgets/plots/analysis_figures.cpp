#include "widgets/plots/analysis_figures.h"

#include <qcustomplot.h>

#include <filesystem>
#include <map>
#include <stdexcept>

#include "core/analysis/compaction.h"
#include "core/analysis/forces.h"
#include "core/analysis/global_sensitivity.h"
#include "core/analysis/identification.h"
#include "core/analysis/rover.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/soil_curves.h"
#include "core/analysis/streaming_identification.h"
#include "core/analysis/stresses.h"
#include "core/analysis/traction.h"
#include "core/analysis/validation.h"
#include "widgets/plots/compaction_figures.h"
#include "widgets/plots/completion.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/gsa_figures.h"
#include "widgets/plots/identification_figures.h"
#include "widgets/plots/rover_figures.h"
#include "widgets/plots/sweep_plot.h"
#include "widgets/plots/traction_figures.h"

namespace terra::ui {
namespace {

template <typename T>
const T& resultOf(const analysis::Outcome& outcome) {
    return std::any_cast<const T&>(outcome.result);
}

[[noreturn]] void unknown(const std::string& type, const std::string& key) {
    throw std::invalid_argument("analysis type \"" + type + "\" has no figure \"" + key + "\"");
}

// The streaming figures draw into two plots: the one asked for and a scratch one.
void drawStreaming(QCustomPlot& plot, const std::string& key,
                   const analysis::StreamingResult& result) {
    if (key != "estimates" && key != "detection") unknown("streaming", key);
    QCustomPlot scratch;
    const bool estimates = key == "estimates";
    StreamingFigures figures(estimates ? &plot : &scratch, estimates ? &scratch : &plot);
    figures.reset(
        result.source.truth.empty() ? QString("Estimates") : QString("Estimates (dotted: truth)"),
        result.frames.size(), result.source.true_border,
        identification::StreamingEstimatorOptions{}.change_threshold);
    figures.setTruth(result.source.truth);
    figures.append(result.frames);
    figures.replot();
}

}  // namespace

void drawAnalysisFigure(QCustomPlot& plot, const std::string& type, const std::string& key,
                        const std::any& settings, const analysis::Outcome& outcome,
                        const QString& title) {
    if (type == "forces") {
        for (const SweepQuantity& q : sweepQuantities()) {
            if (q.column == key) {
                plotSweep(plot, resultOf<analysis::ForcesResult>(outcome).table, q, title);
                return;
            }
        }
    } else if (type == "soil-curves") {
        const auto& curves = resultOf<analysis::SoilCurves>(outcome);
        if (key == "bulldozing") return plotBulldozing(plot, curves, title);
        if (key == "static-sinkage") return plotStaticSinkage(plot, curves, title);
    } else if (type == "stresses") {
        if (key == "stresses") {
            const auto& s = std::any_cast<const analysis::StressSettings&>(settings);
            return plotStresses(plot, resultOf<analysis::StressResult>(outcome), s.stress, title);
        }
    } else if (type == "traction") {
        if (key == "efficiency")
            return plotTraction(plot, resultOf<analysis::TractionResult>(outcome), title);
    } else if (type == "compaction") {
        const auto& r = resultOf<analysis::CompactionResult>(outcome);
        if (key == "profile") return plotCompactionProfile(plot, r, 0, title);  // the envelope
        if (key == "passes") return plotCompactionPasses(plot, r, title);
        if (key == "map") return plotCompactionMap(plot, r, title);
    } else if (type == "sensitivity") {
        const auto& s = std::any_cast<const analysis::SensitivitySettings&>(settings);
        const auto& r = resultOf<analysis::SensitivityResult>(outcome);
        if (key == "Fx" || key == "Fs") {
            return plotSensitivityFamily(plot, r, r.parameter_keys.front(), key + "_N", title);
        }
        if (key == "tornado") return plotTornado(plot, r, s.tornado_slip, title);
    } else if (type == "sensitivity-global") {
        // A script's figure shows the first output at the first slip angle (docs/user-guide.md).
        if (key == "indices") {
            return plotGlobalIndices(plot, resultOf<analysis::GlobalSensitivityResult>(outcome), 0,
                                     0, title);
        }
    } else if (type == "uncertainty-bands") {
        if (key == "bands") {
            return plotUncertaintyBands(plot, resultOf<analysis::UncertaintyBandResult>(outcome), 0,
                                        0, title);
        }
    } else if (type == "identification") {
        const auto& r = resultOf<analysis::IdentificationResult>(outcome);
        if (key == "Fx") return plotIdentification(plot, r, "Fx_N", title);
        if (key == "Fz") return plotIdentification(plot, r, "Fz_N", title);
        if (key == "My") return plotIdentification(plot, r, "My_Nm", title);
    } else if (type == "validation") {
        const auto& r = resultOf<analysis::ValidationResult>(outcome);
        const std::map<std::string, std::string> channels{
            {"Fx", "Fx_N"}, {"sinkage", "sinkage_m"}, {"My", "My_Nm"}, {"Fy", "Fy_N"}};
        if (const auto it = channels.find(key); it != channels.end())
            return plotValidation(plot, r, it->second, title);
    } else if (type == "streaming") {
        return drawStreaming(plot, key, resultOf<analysis::StreamingResult>(outcome));
    } else if (type == "rover") {
        const auto& r = resultOf<analysis::RoverResult>(outcome);
        if (key == "top-view") {
            const std::size_t rows = r.run.series.rows.size();
            return plotRoverTopView(plot, r.scenario, r.run.series, rows == 0 ? 0 : rows - 1,
                                    title);
        }
        for (const RoverFigure& f : roverFigures()) {
            if (f.key == key) return plotRoverFigure(plot, r.run.series, key, title);
        }
    }
    unknown(type, key);
}

QString analysisTitle(const std::string& type, const std::optional<std::string>& title,
                      const analysis::Inputs& inputs, const std::any& settings,
                      const analysis::Outcome& outcome) {
    if (type == "rover") {
        if (title) return QString::fromStdString(*title);
        const auto& r = resultOf<analysis::RoverResult>(outcome);
        return roverTitle(r.scenario.name, r.run.status);
    }
    if (type == "validation") {
        // The test's loads, not the conditions', are the ones plotted.
        if (title) return QString::fromStdString(*title);
        const auto& r = resultOf<analysis::ValidationResult>(outcome);
        const std::string test = std::filesystem::path(r.source).stem().string();
        return QString::fromStdString(inputs.wheel.name + " against the test " + test);
    }
    QString text =
        QString::fromStdString(title.value_or(inputs.soil.name + ", " + inputs.wheel.name)) +
        QString(", W = %1 N").arg(inputs.conditions.load_n);
    if (type == "stresses") {
        const auto& s = std::any_cast<const analysis::StressSettings&>(settings);
        text += QString(", s = %1, β = %2°").arg(s.slip).arg(s.slip_angle_deg);
    } else if (type == "compaction") {
        const auto& s = std::any_cast<const analysis::CompactionSettings&>(settings);
        text += QString(", s = %1, %2 %3")
                    .arg(s.slip)
                    .arg(s.passes)
                    .arg(s.passes == 1 ? "pass" : "passes");
        return compactionTitle(text, resultOf<analysis::CompactionResult>(outcome));
    } else if (type == "sensitivity") {
        const auto& s = std::any_cast<const analysis::SensitivitySettings&>(settings);
        text += QString(", β = %1°").arg(s.slip_angles_deg.front());
    }
    // A study stopped by Ctrl-C keeps what it computed (a refused one has no figure to mark).
    return outcome.status == analysis::Outcome::Status::kCancelled
               ? markedTitle(text, Completion::kCancelled)
               : text;
}

}  // namespace terra::ui
