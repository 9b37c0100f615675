// The compaction panel, offscreen, against the analysis called here with the same inputs and
// settings: the plotted envelope is computeCompaction's, more passes give more points and a
// deeper rut, the settings survive a round trip, the map has the panel's 120 × 60 cells, and a
// cancelled run says so.
#include "widgets/panels/compaction_panel.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QComboBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTemporaryDir>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/project/project.h"
#include "widgets/plots/compaction_figures.h"
#include "widgets/plots/figures.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

// The panel plots kPa of the same doubles: only the division by 1e3 may round.
constexpr double kRelativeTolerance = 1e-12;

QCustomPlot* plotNamed(const CompactionPanel& panel, const QString& name) {
    for (const auto& [key, plot] : panel.plots()) {
        if (key == name) return plot;
    }
    return nullptr;
}

using test::graphNamed;

int itemsOf(const QCustomPlot& plot, const char* class_name) {
    int count = 0;
    for (int i = 0; i < plot.itemCount(); ++i) count += plot.item(i)->inherits(class_name) ? 1 : 0;
    return count;
}

void expectProfile(const QCPGraph& graph, const std::vector<analysis::DepthValues>& rows) {
    ASSERT_EQ(graph.dataCount(), static_cast<int>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double expected = rows[i].max.sigma_z / 1e3;
        EXPECT_DOUBLE_EQ(graph.data()->at(int(i))->key, rows[i].depth_m) << i;
        EXPECT_NEAR(graph.data()->at(int(i))->value, expected,
                    kRelativeTolerance * std::max(1.0, expected))
            << rows[i].depth_m;
    }
}

TEST(CompactionPanel, ProfilePlotIsTheEnvelopeOfComputeCompaction) {
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, test::resources());
    panel.applySettings({{"profile", "loam-moist"}, {"passes", 2}, {"slip", 0.2}});
    ASSERT_TRUE(test::waitForResult(panel));
    ASSERT_TRUE(panel.result().ok()) << panel.result().message;

    analysis::CompactionSettings settings;
    settings.slip = 0.2;
    settings.passes = 2;
    settings.profile = io::resolveProfile(test::resources(), "loam-moist").value();
    const analysis::CompactionResult expected =
        analysis::computeCompaction(project::inputsOf(document.project()), settings);
    ASSERT_GT(expected.envelope.size(), 10u);

    QCustomPlot* plot = plotNamed(panel, "profile");
    ASSERT_NE(plot, nullptr);
    EXPECT_EQ(panel.shownPass(), 0);
    const QCPGraph* sigma_z = graphNamed(*plot, "σ_z");
    ASSERT_NE(sigma_z, nullptr);
    expectProfile(*sigma_z, expected.envelope);
    EXPECT_TRUE(plot->yAxis->rangeReversed());  // depth grows downward
    // The profile's three layers: σ_pc as a step line, green, yellow and red bands each.
    const QCPGraph* precompression = graphNamed(*plot, "σ_pc");
    ASSERT_NE(precompression, nullptr);
    EXPECT_EQ(precompression->dataCount(), 6);
    EXPECT_EQ(itemsOf(*plot, "QCPItemRect"), 9);

    panel.showPass(2);  // a redraw only
    EXPECT_FALSE(panel.isBusy());
    sigma_z = graphNamed(*plot, "σ_z");
    ASSERT_NE(sigma_z, nullptr);
    expectProfile(*sigma_z, expected.passes[1].profile);
    EXPECT_TRUE(plotTitle(*plot).endsWith("pass 2 of 2")) << plotTitle(*plot).toStdString();
    ASSERT_NE(graphNamed(*plot, "σ_pc before pass 2"), nullptr);
}

TEST(CompactionPanel, ThreePassesGiveThreePointsAndADeeperRut) {
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, test::resources());
    ASSERT_TRUE(test::waitForResult(panel));
    ASSERT_EQ(panel.result().passes.size(), 1u);
    const double one_pass_rut_m = panel.result().passes.back().rut_depth_m;

    auto* passes = panel.findChild<QSpinBox*>("compaction.passes");
    ASSERT_NE(passes, nullptr);
    passes->setValue(3);
    ASSERT_TRUE(test::waitForResult(panel));
    ASSERT_TRUE(panel.result().ok()) << panel.result().message;
    QCustomPlot* plot = plotNamed(panel, "passes");
    ASSERT_NE(plot, nullptr);
    ASSERT_EQ(plot->graphCount(), 3);  // sinkage, rut, F_x
    for (int g = 0; g < plot->graphCount(); ++g) EXPECT_EQ(plot->graph(g)->dataCount(), 3) << g;
    const QCPGraph* rut = graphNamed(*plot, "rut after the pass");
    ASSERT_NE(rut, nullptr);
    EXPECT_GT(rut->data()->at(2)->value, rut->data()->at(0)->value);
    EXPECT_DOUBLE_EQ(rut->data()->at(0)->value, one_pass_rut_m * 1e3);  // pass 1 is unchanged
    EXPECT_GT(panel.result().passes.back().rut_depth_m, one_pass_rut_m);
    EXPECT_TRUE(panel.summary().contains("rut after pass 3")) << panel.summary().toStdString();
    EXPECT_TRUE(panel.summary().contains("profile: none")) << panel.summary().toStdString();
}

TEST(CompactionPanel, SettingsRoundTrip) {
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, test::resources());
    panel.applySettings({{"slip", 0.25},
                         {"slip_angle_deg", 5.0},
                         {"passes", 3},
                         {"profile", "loam-moist"},
                         {"concentration", 4.0},
                         {"width", "parabolic"},
                         {"map_pass", 2}});
    const nlohmann::json saved = panel.settings();
    EXPECT_EQ(saved["passes"], 3);
    EXPECT_EQ(saved["concentration"], 4.0);
    EXPECT_EQ(saved["width"], "parabolic");
    EXPECT_EQ(saved["map_pass"], 2);
    EXPECT_EQ(saved["map_points"], nlohmann::json({120, 60}));
    ASSERT_TRUE(saved.contains("profile"));
    EXPECT_EQ(saved["profile"]["name"], "loam, moist");

    CompactionPanel reopened(&document, test::resources());
    reopened.applySettings({{"concentration", 6.0}, {"profile", "clay-wet"}});
    reopened.applySettings(saved);
    EXPECT_EQ(reopened.settings(), saved);
    auto* profile = reopened.findChild<QComboBox*>("compaction.profile");
    ASSERT_NE(profile, nullptr);
    EXPECT_EQ(profile->currentText(), "loam-moist");  // the preset, not a copy of it

    // A whole object without ν and profile (per layer, none) clears them; a partial one keeps.
    const nlohmann::json whole = analysis::toJson(analysis::CompactionSettings{});
    reopened.applySettings(whole);
    EXPECT_FALSE(reopened.settings().contains("concentration"));
    EXPECT_FALSE(reopened.settings().contains("profile"));
    reopened.applySettings(saved);
    reopened.applySettings({{"passes", 2}});
    EXPECT_EQ(reopened.settings()["passes"], 2);
    EXPECT_EQ(reopened.settings()["concentration"], 4.0);
    EXPECT_EQ(reopened.settings()["profile"], saved["profile"]);
    EXPECT_EQ(reopened.settings()["map_pass"], 2);
}

// The panel's settings go into the project and a saved project with them opens again (the
// "panels" reader accepts "compaction").
TEST(CompactionPanel, SavedSettingsOpenWithTheProject) {
    QTemporaryDir dir;
    const io::PresetLocations locations = test::resources();
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, locations);
    panel.applySettings({{"profile", "sandy-loam-moist"}, {"passes", 4}});
    ASSERT_TRUE(document.project().panels.contains("compaction"));
    EXPECT_EQ(document.project().panels["compaction"], panel.settings());
    QString error;
    ASSERT_TRUE(document.save(dir.filePath("c.terra"), &error)) << error.toStdString();
    const auto opened = ProjectDocument::load(dir.filePath("c.terra"), &locations);
    ASSERT_TRUE(opened.ok()) << opened.message();
    EXPECT_EQ(opened->panels["compaction"], panel.settings());
}

TEST(CompactionPanel, MapHas120By60CellsOfTheResultsSigmaZ) {
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, test::resources());
    panel.resize(800, 600);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    QCustomPlot* plot = plotNamed(panel, "map");
    ASSERT_NE(plot, nullptr);
    ASSERT_EQ(plot->plottableCount(), 1);
    auto* map = qobject_cast<QCPColorMap*>(plot->plottable(0));
    ASSERT_NE(map, nullptr);
    EXPECT_EQ(map->data()->keySize(), 120);
    EXPECT_EQ(map->data()->valueSize(), 60);
    const Table& table = panel.result().map;
    ASSERT_EQ(table.rows.size(), 120u * 60u);
    double highest = 0.0;
    for (const auto& row : table.rows)
        highest = std::max(highest, row[table.column("sigma_z_kPa")]);
    EXPECT_DOUBLE_EQ(map->dataRange().upper, highest);
    // Nearest the surface, straight below the contact: the cell of the table's largest σ_z.
    const std::size_t largest = static_cast<std::size_t>(std::distance(
        table.rows.begin(),
        std::max_element(table.rows.begin(), table.rows.end(), [&](const auto& a, const auto& b) {
            return a[table.column("sigma_z_kPa")] < b[table.column("sigma_z_kPa")];
        })));
    EXPECT_DOUBLE_EQ(map->data()->cell(int(largest % 120), int(largest / 120)), highest);
    EXPECT_TRUE(plot->yAxis->rangeReversed());

    // The profile's legend sits off the data.
    QCustomPlot* profile = plotNamed(panel, "profile");
    profile->replot();
    EXPECT_TRUE(profile->legend->visible());
    EXPECT_FALSE(profile->legend->outerRect().intersects(profile->axisRect()->rect()));
}

TEST(CompactionPanel, ACancelledRunSaysSoInTheTitlesAndTheSummary) {
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, test::resources());
    ASSERT_TRUE(test::waitForResult(panel));
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    panel.applySettings({{"passes", 50}});
    ASSERT_TRUE(busy.wait(5000));
    panel.cancelRunning();  // before the first of 50 passes ends
    ASSERT_TRUE(shown.count() > 0 || shown.wait(30000));
    ASSERT_FALSE(panel.result().ok());
    EXPECT_LT(panel.result().passes.size(), 50u);
    EXPECT_TRUE(plotTitle(*plotNamed(panel, "profile")).endsWith("CANCELLED (partial)"))
        << plotTitle(*plotNamed(panel, "profile")).toStdString();
    EXPECT_TRUE(plotTitle(*plotNamed(panel, "passes")).endsWith("CANCELLED (partial)"));
    EXPECT_TRUE(panel.summary().contains("CANCELLED")) << panel.summary().toStdString();
}

// Issue 27: nothing heavy starts by itself on opening. A project may ask for 1000 passes (the
// panel's box stops at 50): that run waits for Compute; the most the box gives still starts.
TEST(CompactionPanel, ALongRunFromAProjectWaitsForCompute) {
    ProjectDocument document;
    test::resetToDefault(document);
    Project project = document.project();
    project.panels["compaction"] = {{"passes", 1000}};
    document.reset(project);
    CompactionPanel panel(&document, test::resources());
    panel.applySettings(document.project().panels["compaction"]);
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    panel.resize(800, 600);
    panel.show();
    EXPECT_FALSE(busy.wait(1000)) << "a 1000-pass run started by itself";
    EXPECT_FALSE(panel.hasResult());
    EXPECT_TRUE(panel.computeButton()->isVisible());
    EXPECT_TRUE(panel.summary().startsWith("Not computed: 1000 passes at 19 depths"))
        << panel.summary().toStdString();
    EXPECT_EQ(plotTitle(*plotNamed(panel, "profile")), "Not computed: press Compute");
    // Compute starts it (cancelled here: the point is that it runs).
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    panel.computeButton()->click();
    ASSERT_TRUE(busy.count() > 0 || busy.wait(5000));
    panel.cancelRunning();
    ASSERT_TRUE(shown.count() > 0 || shown.wait(30000));
    EXPECT_FALSE(panel.computeButton()->isVisible());
    // 50 passes, the box's largest: starts by itself (50 × 19 ≤ kAutomaticPassDepths).
    static_assert(CompactionPanel::kMaxPasses * 19 <= CompactionPanel::kAutomaticPassDepths);
    busy.clear();
    panel.applySettings({{"passes", CompactionPanel::kMaxPasses}});
    EXPECT_TRUE(busy.count() > 0 || busy.wait(5000)) << "50 passes did not start by itself";
    panel.cancelRunning();
    EXPECT_TRUE(test::waitForResult(panel));
}

}  // namespace
}  // namespace terra::ui
