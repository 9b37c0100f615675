// "Compare with…" of the forces panel on real widgets (QT_QPA_PLATFORM=offscreen): a pinned or
// preset reference soil drawn dashed over the project's curves, kept while the soil is edited,
// computed as the core computes it, cleared, and carried with its name by exports and Copy data.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAction>
#include <QApplication>
#include <QClipboard>
#include <QFile>
#include <QMenu>
#include <QPushButton>
#include <QTemporaryDir>
#include <QToolButton>
#include <cmath>

#include "core/analysis/forces.h"
#include "core/analysis/soil_curves.h"
#include "core/common/units.h"
#include "core/io/csv.h"
#include "core/project/project.h"
#include "widgets/editors/property_editors.h"
#include "widgets/editors/validated_spin_box.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/plots/plot_export.h"
#include "widgets/plots/plot_menu.h"
#include "widgets/plots/reference_overlay.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

using test::namedPlot;

std::vector<QCPGraph*> graphsNamed(QCustomPlot& plot, const QString& object_name) {
    std::vector<QCPGraph*> out;
    for (int i = 0; i < plot.graphCount(); ++i) {
        if (plot.graph(i)->objectName() == object_name) out.push_back(plot.graph(i));
    }
    return out;
}

// The F_x of a sweep table at (β, s), by the table's columns.
double fxAt(const Table& t, double beta_deg, double slip) {
    for (const auto& row : t.rows) {
        if (row[t.column("slip_angle_deg")] == beta_deg &&
            std::abs(row[t.column("slip")] - slip) < 1e-12)
            return row[t.column("Fx_N")];
    }
    return NAN;
}

TEST(ForcesComparison, PinnedSoilKeepsItsCurvesWhileTheProjectSoilIsEdited) {
    ProjectDocument document;
    test::resetToDefault(document);
    const Project original = document.project();
    ForcesPanel panel(&document);
    SoilEditor editor(&document, test::resources());
    panel.resize(1000, 650);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    QCustomPlot* fx = namedPlot(panel, "Fx_N-vs-slip");
    ASSERT_NE(fx, nullptr);
    EXPECT_TRUE(graphsNamed(*fx, "reference").empty());
    EXPECT_FALSE(panel.clearComparisonButton()->isEnabled());
    const double project_before = fx->graph(0)->data()->at(50)->value;  // β = 5°, s = 0.5

    // Pinned from the button's menu, as a user does.
    QAction* pin = panel.compareButton()->menu()->findChild<QAction*>("forces.compare_pin");
    ASSERT_NE(pin, nullptr);
    pin->trigger();
    EXPECT_EQ(panel.referenceName(), "sandy loam (before edit)");
    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_TRUE(panel.clearComparisonButton()->isEnabled());
    // One dashed curve per slip angle, one legend entry for them all.
    std::vector<QCPGraph*> reference = graphsNamed(*fx, "reference");
    ASSERT_EQ(reference.size(), 6u);
    EXPECT_EQ(reference[0]->name(), "sandy loam (before edit), dashed");
    EXPECT_EQ(reference[1]->name(), QString::fromUtf8("sandy loam (before edit), β = 10°"));
    EXPECT_EQ(reference[0]->pen().style(), Qt::DashLine);
    EXPECT_EQ(reference[0]->pen().color(), fx->graph(0)->pen().color());  // same β, same colour
    EXPECT_TRUE(fx->legend->hasItemWithPlottable(reference[0]));
    EXPECT_FALSE(fx->legend->hasItemWithPlottable(reference[1]));
    EXPECT_DOUBLE_EQ(reference[0]->data()->at(50)->value, project_before);

    editor.spinBox("phi_deg")->setValue(35.0);
    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_EQ(document.project().soil.name, "sandy loam (edited)");
    // The project's curve follows the edit (more friction, more drawbar pull, Fig. 4.3)...
    const double project_after = fx->graph(0)->data()->at(50)->value;
    EXPECT_GT(project_after, project_before + 1.0);
    // ...the reference keeps the soil it was pinned with: the core's sweep of the original
    // project, computed here on its own.
    reference = graphsNamed(*fx, "reference");
    ASSERT_EQ(reference.size(), 6u);
    const analysis::ForcesResult core_sweep =
        analysis::computeForceSweep(project::inputsOf(original), {});
    const double core_fx = fxAt(core_sweep.table, 5.0, 0.5);
    ASSERT_TRUE(std::isfinite(core_fx));
    EXPECT_NEAR(reference[0]->data()->at(50)->value, core_fx, 1e-9);
    EXPECT_NEAR(fxAt(panel.referenceSweep(), 30.0, 0.5), fxAt(core_sweep.table, 30.0, 0.5), 1e-9);
    EXPECT_NEAR(reference[0]->data()->at(50)->value, project_before, 1e-9);
    // The soil plots carry it too: F_b of the pinned soil (φ = 29°, not 35°).
    QCustomPlot* fb = namedPlot(panel, "Fb-vs-sinkage");
    std::vector<QCPGraph*> fb_reference = graphsNamed(*fb, "reference");
    ASSERT_EQ(fb_reference.size(), 1u);
    EXPECT_EQ(fb_reference[0]->name(), "sandy loam (before edit), Bekker");
    const analysis::SoilCurves core_soil = analysis::computeSoilCurves(project::inputsOf(original));
    const Table& b = core_soil.bulldozing;
    EXPECT_NEAR(fb_reference[0]->data()->at(30)->value, b.rows[30][b.column("Fb_bekker_N")], 1e-9);
    EXPECT_GT(fb->graph(0)->data()->at(30)->value,
              fb_reference[0]->data()->at(30)->value);  // c_s grows with φ (Eq. 2.30)

    // Copy data and the export: the project's rows and the reference's, each named.
    const Table table = panel.currentTable();
    ASSERT_EQ(table.label_column, "soil");
    ASSERT_EQ(table.rows.size(), 1200u);
    EXPECT_EQ(table.labels.front(), "sandy loam (edited)");
    EXPECT_EQ(table.labels.back(), "sandy loam (before edit)");
    EXPECT_NEAR(table.rows[600 + 50][table.column("Fx_N")], core_fx, 1e-9);
    QMenu* menu = makePlotMenu(*fx, {[&] { return panel.currentTable(); }, [] {}}, &panel);
    menu->findChild<QAction*>("plot.copy_data")->trigger();
    const QString csv = QApplication::clipboard()->text();
    EXPECT_TRUE(csv.startsWith("soil,slip")) << csv.left(80).toStdString();
    EXPECT_EQ(csv.count("sandy loam (before edit)"), 600);
    EXPECT_EQ(csv.count("sandy loam (edited)"), 600);
    QTemporaryDir dir;
    const QString path = dir.filePath("fx.csv");
    QString error;
    ASSERT_TRUE(exportTable(panel.currentTable(), path, &error)) << error.toStdString();
    QFile file(path);
    ASSERT_TRUE(file.open(QIODevice::ReadOnly));
    EXPECT_EQ(QString::fromUtf8(file.readAll()).count("sandy loam (before edit)"), 600);

    // Clear: the reference goes from every plot and from the data.
    panel.clearComparisonButton()->click();
    EXPECT_TRUE(panel.referenceName().isEmpty());
    ASSERT_TRUE(test::waitForResult(panel));
    for (const auto& [name, plot] : panel.plots())
        EXPECT_TRUE(graphsNamed(*plot, "reference").empty()) << name.toStdString();
    EXPECT_EQ(fx->graphCount(), 6);
    EXPECT_TRUE(panel.currentTable().label_column.empty());
    EXPECT_EQ(panel.currentTable().rows.size(), 600u);
    EXPECT_FALSE(panel.clearComparisonButton()->isEnabled());
    EXPECT_DOUBLE_EQ(fx->graph(0)->data()->at(50)->value, project_after);
}

TEST(ForcesComparison, APresetIsSweptWithTheProjectsWheelAndConditions) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    panel.setPresetLocations(test::resources());
    panel.resize(1000, 650);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    ASSERT_TRUE(document.setLoad(60.0));
    ASSERT_TRUE(test::waitForResult(panel));
    panel.compareButton()->menu()->aboutToShow();  // the menu lists the presets when it opens
    QAction* clay =
        panel.compareButton()->menu()->findChild<QAction*>("forces.compare_preset.clayey-soil");
    ASSERT_NE(clay, nullptr);
    clay->trigger();
    ASSERT_TRUE(test::waitForResult(panel));
    const Result<soil::SoilParameters> soil = io::resolveSoil(test::resources(), "clayey-soil");
    ASSERT_TRUE(soil);
    EXPECT_EQ(panel.referenceName(), QString::fromStdString(soil->name));
    Project expected = document.project();
    expected.soil = *soil;
    const analysis::ForcesResult core =
        analysis::computeForceSweep(project::inputsOf(expected), {});
    ASSERT_EQ(panel.referenceSweep().rows.size(), core.table.rows.size());
    EXPECT_NEAR(fxAt(panel.referenceSweep(), 5.0, 0.5), fxAt(core.table, 5.0, 0.5), 1e-9);
    // Different soils: different drawbar pull at the same wheel, load and slip.
    EXPECT_GT(
        std::abs(fxAt(panel.referenceSweep(), 5.0, 0.5) - fxAt(panel.result().table, 5.0, 0.5)),
        0.1);
    // A load edit sweeps the reference again at the new load (it is reused only while its soil,
    // the wheel and the conditions are unchanged, e.g. while the project's soil is edited).
    ASSERT_TRUE(document.setLoad(75.0));
    ASSERT_TRUE(test::waitForResult(panel));
    expected.conditions.load_n = 75.0;
    const analysis::ForcesResult at_75 =
        analysis::computeForceSweep(project::inputsOf(expected), {});
    EXPECT_NEAR(fxAt(panel.referenceSweep(), 5.0, 0.5), fxAt(at_75.table, 5.0, 0.5), 1e-9);
    EXPECT_GT(std::abs(fxAt(at_75.table, 5.0, 0.5) - fxAt(core.table, 5.0, 0.5)), 1e-3);
    // A preset that does not exist is refused with a message, the comparison stays.
    QString error;
    EXPECT_FALSE(panel.compareWithPreset("no-such-soil", &error));
    EXPECT_FALSE(error.isEmpty());
    EXPECT_EQ(panel.referenceName(), QString::fromStdString(soil->name));
}

TEST(ForcesComparison, AMeasuredTestStaysOverTheReferenceAndBothGoIntoTheData) {
    QTemporaryDir dir;
    const QString path = dir.filePath("test.csv");
    {
        QFile file(path);
        ASSERT_TRUE(file.open(QIODevice::WriteOnly));
        file.write("load_N,slip,slip_angle_deg,Fx_N\n40,0.1,0,1.5\n40,0.3,0,3\n");
    }
    ProjectDocument document;
    test::resetToDefault(document);
    QString error;
    ASSERT_TRUE(document.setExperiment(path, &error)) << error.toStdString();
    ForcesPanel panel(&document);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    panel.pinReference();
    ASSERT_TRUE(test::waitForResult(panel));
    QCustomPlot* fx = namedPlot(panel, "Fx_N-vs-slip");
    EXPECT_EQ(graphsNamed(*fx, "reference").size(), 6u);
    ASSERT_EQ(graphsNamed(*fx, "measured").size(), 1u);
    // The measured points are drawn last, over every curve.
    EXPECT_EQ(fx->graph(fx->graphCount() - 1)->objectName(), "measured");
    const Table t = panel.currentTable();
    // 600 project rows, 100 of the model at 40 N, β = 0°, 2 measured, then 600 of the reference.
    ASSERT_EQ(t.rows.size(), 600u + 100u + 2u + 600u);
    const std::size_t measured = t.column("measured"), load = t.column("load_N");
    EXPECT_EQ(t.labels[701], "sandy loam");
    EXPECT_DOUBLE_EQ(t.rows[701][measured], 1.0);
    EXPECT_EQ(t.labels[702], "sandy loam (before edit)");
    EXPECT_DOUBLE_EQ(t.rows[702][measured], 0.0);
    EXPECT_DOUBLE_EQ(t.rows[702][load], document.project().conditions.load_n);
}

TEST(ReferenceOverlay, TableWithReferenceMatchesColumnsByNameAndNamesEachRow) {
    Table shown{{"slip", "Fx_N", "load_N", "measured"},
                {{0.1, 5.0, 80.0, 0.0}, {0.2, 7.0, 80.0, 1.0}}};
    Table reference{{"Fx_N", "slip", "extra"}, {{3.0, 0.1, 9.0}}};
    const Table t = tableWithReference(shown, "mine", reference, "theirs", 60.0);
    ASSERT_EQ(t.rows.size(), 3u);
    EXPECT_EQ(t.columns, shown.columns);
    EXPECT_EQ(t.labels, (std::vector<std::string>{"mine", "mine", "theirs"}));
    EXPECT_EQ(t.rows[2], (std::vector<double>{0.1, 3.0, 60.0, 0.0}));
    const std::string csv = io::toCsv(t);
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "soil,slip,Fx_N,load_N,measured");
}

}  // namespace
}  // namespace terra::ui
