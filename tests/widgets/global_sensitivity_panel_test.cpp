// The global sensitivity panel on real widgets: it computes off the GUI thread and plots finite
// bars with whiskers, its bands enclose the nominal curve (the project soil's own forces, from
// the contact model), a cancel keeps the panel usable, and the identified soil's covariance is a
// source of the parameters.
#include "widgets/panels/global_sensitivity_panel.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>
#include <unistd.h>

#include <QSignalSpy>
#include <QTest>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "../app/cli_runner.h"
#include "core/analysis/sweep.h"
#include "core/common/units.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/project/panels.h"
#include "widgets/plots/figures.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

int finiteBars(QCustomPlot& plot, int* bars_out = nullptr) {
    int finite = 0, bars = 0;
    for (int i = 0; i < plot.plottableCount(); ++i) {
        auto* b = qobject_cast<QCPBars*>(plot.plottable(i));
        if (!b) continue;
        ++bars;
        for (int k = 0; k < b->dataCount(); ++k)
            finite += std::isfinite(b->data()->at(k)->value) ? 1 : 0;
    }
    if (bars_out) *bars_out = bars;
    return finite;
}

TEST(GlobalSensitivityPanel, ComputesOffTheGuiThreadAndPlotsFiniteBarsWithWhiskers) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.resize(1000, 600);
    panel.setSamples(128);
    panel.setSlips("0.1,0.3,0.6");
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    ASSERT_TRUE(panel.indices().has_value());
    const analysis::GlobalSensitivityResult& r = *panel.indices();
    ASSERT_EQ(r.status(), gsa::StudyStatus::kCompleted) << r.message();
    // Four ticked parameters × (S1, ST) bars, each with one value per slip, all finite.
    int bars = 0;
    EXPECT_EQ(finiteBars(*panel.currentPlot(), &bars), 4 * 2 * 3);
    EXPECT_EQ(bars, 8);
    int whiskers = 0;
    for (int i = 0; i < panel.currentPlot()->plottableCount(); ++i)
        whiskers += qobject_cast<QCPErrorBars*>(panel.currentPlot()->plottable(i)) ? 1 : 0;
    EXPECT_EQ(whiskers, 8);
    // The bars are the study's numbers: S1 of φ at s = 0.1 is the first bar's first value.
    auto* s1_phi = qobject_cast<QCPBars*>(panel.currentPlot()->plottable(0));
    ASSERT_NE(s1_phi, nullptr);
    EXPECT_EQ(s1_phi->data()->at(0)->value, r.sobol->indices.first_order(0, 0));
    EXPECT_EQ(panel.currentTable().rows.size(), 3u);
}

TEST(GlobalSensitivityPanel, BandsEncloseTheNominalCurve) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.resize(1000, 600);
    // Ranges around the sandy loam's own φ and c, so the nominal soil lies inside the sample.
    ASSERT_TRUE(panel.setRange("phi_deg", true, 26.0, 32.0));
    ASSERT_TRUE(panel.setRange("c_kPa", true, 1.2, 2.2));
    ASSERT_TRUE(panel.setRange("K_m", false, 0.01, 0.03));
    ASSERT_TRUE(panel.setRange("n", false, 0.6, 0.8));
    EXPECT_FALSE(panel.setRange("no_such_key", true, 0, 1));
    panel.setSamples(64);
    panel.showPage(1);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));  // the first show's computation
    if (!panel.bands()) {
        panel.compute();
        ASSERT_TRUE(test::waitForResult(panel));
    }
    ASSERT_TRUE(panel.bands().has_value());
    const analysis::UncertaintyBandResult& b = *panel.bands();
    ASSERT_TRUE(b.bands.usable()) << b.bands.message;
    const Table t = b.table();
    const Project& p = document.project();
    // The nominal curve against an independent sweep of the project soil (core sweepSlip).
    analysis::SweepSpec spec;
    spec.slips = b.bands.grid.slips;
    spec.slip_angles_rad = {0.0};
    spec.load_n = p.conditions.load_n;
    const analysis::SweepResult sweep = analysis::sweepSlip(project::inputsOf(p).contact(), spec);
    ASSERT_EQ(sweep.table.rows.size(), t.rows.size());
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        const double nominal = t.rows[i][t.column("Fx_N_nominal")];
        EXPECT_NEAR(nominal, sweep.table.rows[i][sweep.table.column("Fx_N")],
                    1e-6 * std::max(1.0, std::abs(nominal)))
            << i;
        EXPECT_LE(t.rows[i][t.column("Fx_N_p5")], nominal + 1e-9) << i;
        EXPECT_GE(t.rows[i][t.column("Fx_N_p95")], nominal - 1e-9) << i;
    }
    // On screen: the filled band, the median and the nominal curve, every point finite.
    QCustomPlot* plot = panel.currentPlot();
    ASSERT_GE(plot->graphCount(), 4);
    for (int g = 0; g < plot->graphCount(); ++g) {
        ASSERT_EQ(plot->graph(g)->dataCount(), static_cast<int>(t.rows.size()));
        for (int k = 0; k < plot->graph(g)->dataCount(); ++k)
            EXPECT_TRUE(std::isfinite(plot->graph(g)->data()->at(k)->value));
    }
}

TEST(GlobalSensitivityPanel, CancelStopsTheStudyAndTheNextOneRuns) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.setSamples(1 << 16);  // long enough to be cancelled (and too long to start by itself)
    panel.show();
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    panel.compute();
    ASSERT_TRUE(busy.wait(5000));
    panel.cancelRunning();
    ASSERT_TRUE(test::waitForResult(panel, 30000));
    ASSERT_TRUE(panel.indices().has_value());
    EXPECT_EQ(panel.indices()->status(), gsa::StudyStatus::kCancelled);
    panel.setSamples(32);
    panel.compute();
    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_EQ(panel.indices()->status(), gsa::StudyStatus::kCompleted);
}

// Issue 27: a project's 100,000 samples (1.8 M model evaluations) started on the first show.
TEST(GlobalSensitivityPanel, AHeavyStudyWaitsForComputeAndSaysSo) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.resize(1000, 600);
    panel.applySettings({{"samples", 100000}});
    EXPECT_EQ(panel.plannedEvaluations(), 100000u * 6u * 3u);
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    panel.show();
    QTest::qWait(300);
    EXPECT_EQ(busy.count(), 0) << "the study started by itself";
    EXPECT_FALSE(panel.indices().has_value());
    EXPECT_TRUE(panel.statusText().contains("1,800,000 model evaluations"))
        << panel.statusText().toStdString();
    EXPECT_EQ(plotTitle(*panel.currentPlot()), "Not computed: press Compute");
    // Asked, it runs (cancelled here: what it computed is kept).
    panel.compute();
    ASSERT_TRUE(busy.wait(5000));
    panel.cancelRunning();
    ASSERT_TRUE(test::waitForResult(panel, 60000));
    EXPECT_EQ(panel.indices()->status(), gsa::StudyStatus::kCancelled);
}

TEST(GlobalSensitivityPanel, IdentifiedCovarianceIsASource) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    const soil::SoilParameters& soil = document.project().soil;
    identification::DecoupledParameters p;
    p.a0 = soil.max_stress_a0;
    p.a1 = soil.max_stress_a1;
    p.n0 = soil.sinkage_exponent;
    p.pressure_modulus =
        soil.cohesive_modulus / document.project().wheel.width_m + soil.frictional_modulus;
    p.cohesion_pa = soil.cohesion_pa;
    p.friction_angle_rad = soil.friction_angle_rad;
    p.shear_modulus_m = soil.shear_modulus_m;
    identification::Uncertainty u;
    u.computed = true;
    u.std[identification::kPhi] = units::degToRad(1.0);
    u.std[identification::kC] = 150.0;
    for (auto& row : u.correlation) row.fill(0.0);
    u.correlation[identification::kPhi][identification::kC] = -0.5;
    u.correlation[identification::kC][identification::kPhi] = -0.5;
    panel.setIdentification(p, u);
    panel.setSource(1);
    panel.setSamples(64);
    panel.showPage(1);
    const analysis::UncertaintyBandSettings s = panel.bandSettings();
    ASSERT_TRUE(s.study.correlated.has_value());
    EXPECT_TRUE(s.study.parameters.empty());
    EXPECT_EQ(s.study.correlated->keys, (std::vector<std::string>{"c_kPa", "phi_deg"}));
    EXPECT_NEAR(s.study.correlated->covariance[1][1], 1.0, 1e-12);  // σ_φ = 1°
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    if (!panel.bands()) {
        panel.compute();
        ASSERT_TRUE(test::waitForResult(panel));
    }
    ASSERT_TRUE(panel.bands().has_value());
    EXPECT_TRUE(panel.bands()->bands.usable()) << panel.bands()->bands.message;
}

// One computation: the panel's indices and a script's "sensitivity-global" analysis with the same
// settings, through the real executable, give the same table value for value.
TEST(GlobalSensitivityPanel, SameTableAsTheScriptAnalysis) {
    namespace fs = std::filesystem;
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.setSamples(128);
    panel.setSlips("0.2,0.5");
    ASSERT_TRUE(test::waitForResult(panel));
    ASSERT_TRUE(panel.indices().has_value());
    const fs::path dir =
        fs::temp_directory_path() / ("terra_gsa_panel_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const nlohmann::json script = {
        {"soil", "sandy-loam"},
        {"wheel", "A"},
        {"export", {{"width", 400}, {"height", 300}}},
        {"analyses",
         {{{"name", "gsa"},
           {"type", "sensitivity-global"},
           {"outputs", {"Fx_N", "Fs_N", "My_Nm", "sinkage_m", "entry_angle_deg", "Fz_N"}},
           {"slips", {0.2, 0.5}},
           {"load_N", document.project().conditions.load_n},
           {"samples", 128}}}}};
    ASSERT_FALSE(io::writeFileAtomically(dir / "script.json", script.dump(2)));
    const terra::test::CliRun r = terra::test::run("run " + (dir / "script.json").string() +
                                                   " --out " + (dir / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    Result<io::CsvDocument> read = io::readCsv(dir / "out" / "gsa.csv");
    ASSERT_TRUE(read.ok()) << read.message();
    const Table t = panel.currentTable();
    EXPECT_EQ(t.columns, read->header);
    ASSERT_EQ(t.rows.size(), read->rows.size());
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        for (std::size_t j = 0; j < t.columns.size(); ++j) {
            double value = 0.0;
            ASSERT_TRUE(io::parseNumber(read->rows[i][j], value));
            EXPECT_EQ(t.rows[i][j], value) << i << " " << t.columns[j];
        }
    }
    fs::remove_all(dir);
}

TEST(GlobalSensitivityPanel, SettingsRoundTripThroughTheProjectReader) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.setMethod(analysis::GsaMethod::kMorris);
    panel.setSlips("0.2,0.4");
    panel.showPage(1);
    const nlohmann::json saved = panel.settings();
    const auto read =
        project::panelSettingsFromJson<project::GlobalSensitivityPanelSettings>(saved);
    ASSERT_TRUE(read) << formatIssues(read.issues());
    EXPECT_EQ(read.value().method, "morris");
    EXPECT_EQ(read.value().page, "bands");
    EXPECT_EQ(read.value().slips, (std::vector<double>{0.2, 0.4}));
    GlobalSensitivityPanel other(&document);
    other.applySettings(saved);
    EXPECT_EQ(other.settings(), saved);
}

}  // namespace
}  // namespace terra::ui
