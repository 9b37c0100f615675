// Every figure the registry declares (core/analysis/registry.h) is drawn by
// drawAnalysisFigure from that type's outcome: a script can ask for any of them.
#include "widgets/plots/analysis_figures.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include "core/analysis/registry.h"
#include "core/project/project.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

TEST(AnalysisFigures, EveryDeclaredFigureOfEveryTypeIsDrawn) {
    const io::PresetLocations locations = test::resources();
    const analysis::ReadContext context{&locations, {}};
    analysis::Inputs inputs = project::inputsOf(ProjectDocument::defaultProject(locations));
    inputs.conditions.slip_angles_deg = {5.0};
    inputs.conditions.slip_count = 10;
    for (const analysis::AnalysisType& type : analysis::analysisTypes()) {
        // Small settings: a short rover run, few slips for the sweeps and the fits.
        nlohmann::json settings = nlohmann::json::object();
        if (type.name == "rover") settings = {{"scenario", "straight"}, {"duration_s", 0.5}};
        if (type.name == "validation")
            settings = {{"experiments", std::string(TERRA_RESOURCE_DIR) +
                                            "/experiments/ding2011-smooth-hit-lss1-80N.csv"}};
        if (type.name == "compaction") settings["map_points"] = {20, 10};  // the map is opt-in
        if (type.name == "sensitivity" || type.name == "identification")
            settings["slip_count"] = 10;
        std::vector<Issue> issues;
        io::ObjectReader r(settings, issues);
        const std::any read = type.read(r, context);
        r.finish();
        ASSERT_TRUE(issues.empty()) << type.name << ": " << formatIssues(issues);
        const analysis::Outcome outcome = type.run(read, inputs, {});
        const QString title = analysisTitle(type.name, std::nullopt, inputs, read, outcome);
        EXPECT_FALSE(title.isEmpty()) << type.name;
        for (const analysis::FigureSpec& figure : type.figures) {
            QCustomPlot plot;
            plot.resize(400, 300);
            EXPECT_NO_THROW(drawAnalysisFigure(plot, type.name, figure.key, read, outcome, title))
                << type.name << " " << figure.key;
            int drawn = 0;
            for (int i = 0; i < plot.plottableCount(); ++i) {
                drawn += plot.plottable(i)->interface1D() &&
                         plot.plottable(i)->interface1D()->dataCount() > 0;
                // A heat map holds 2-D data (the compaction map).
                if (const auto* map = qobject_cast<QCPColorMap*>(plot.plottable(i)))
                    drawn += map->data()->keySize() > 0 && map->data()->valueSize() > 0;
            }
            EXPECT_GT(drawn, 0) << type.name << " " << figure.key << ": nothing drawn";
        }
        QCustomPlot plot;
        EXPECT_THROW(drawAnalysisFigure(plot, type.name, "no-such-figure", read, outcome, title),
                     std::invalid_argument)
            << type.name;
    }
}

}  // namespace
}  // namespace terra::ui
