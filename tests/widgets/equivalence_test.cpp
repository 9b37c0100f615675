// One implementation per analysis: each analysis computed by the studio's panel (offscreen) and
// by `terrastudio run` (the real executable) with the same project and settings gives the same
// tables, value for value (the CSV writes every double in its shortest round-trip form).
#include <gtest/gtest.h>
#include <unistd.h>

#include <QSignalSpy>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../app/cli_runner.h"
#include "core/analysis/stresses.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Sandy loam on wheel A under conditions other than the defaults, in the project and the script.
project::Project testProject() {
    project::Project p = ProjectDocument::defaultProject(test::resources());
    p.conditions.load_n = 50.0;
    p.conditions.slip_angles_deg = {5.0, 20.0};
    p.conditions.slip_count = 40;
    p.conditions.slip_max = 0.9;
    return p;
}

class Equivalence : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("terra_equivalence_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        document_.reset(testProject());
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs one analysis through `terrastudio run` on the test project's soil, wheel and
    // conditions; its outputs are in dir_/out.
    void runScript(const json& analysis) {
        const project::Project p = testProject();
        const json script = {{"soil", "sandy-loam"},
                             {"wheel", "A"},
                             {"conditions", analysis::toJson(p.conditions)},
                             {"export", {{"width", 400}, {"height", 300}}},
                             {"analyses", json::array({analysis})}};
        const fs::path path = dir_ / "script.json";
        ASSERT_FALSE(io::writeFileAtomically(path, script.dump(2)));
        const terra::test::CliRun r = terra::test::run("run " + path.string() + " --out " +
                                                       (dir_ / "out").string() + " --format png");
        ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    }

    // A CSV the run wrote, as a table (empty cells: NaN, as the writer writes them).
    Table csv(const std::string& name) const {
        Result<io::CsvDocument> read = io::readCsv(dir_ / "out" / name);
        EXPECT_TRUE(read.ok()) << name << ": " << read.message();
        Table t;
        if (!read) return t;
        t.columns = read->header;
        // A tornado's first column is its text label column (Table::label_column).
        const bool labelled = !t.columns.empty() && t.columns.front() == "parameter";
        if (labelled) {
            t.label_column = t.columns.front();
            t.columns.erase(t.columns.begin());
        }
        for (const auto& cells : read->rows) {
            std::vector<double> row;
            for (std::size_t k = 0; k < cells.size(); ++k) {
                const std::string& cell = cells[k];
                if (labelled && k == 0) {
                    t.labels.push_back(cell);
                    continue;
                }
                double value = std::nan("");
                if (!cell.empty()) {
                    EXPECT_TRUE(io::parseNumber(cell, value)) << name << ": " << cell;
                }
                row.push_back(value);
            }
            t.rows.push_back(std::move(row));
        }
        return t;
    }

    static void expectSame(const Table& panel, const Table& cli, const std::string& what) {
        ASSERT_EQ(panel.columns, cli.columns) << what;
        ASSERT_EQ(panel.label_column, cli.label_column) << what;
        ASSERT_EQ(panel.labels, cli.labels) << what;
        ASSERT_EQ(panel.rows.size(), cli.rows.size()) << what;
        ASSERT_GT(panel.rows.size(), 0u) << what;
        for (std::size_t i = 0; i < panel.rows.size(); ++i) {
            for (std::size_t j = 0; j < panel.columns.size(); ++j) {
                const double a = panel.rows[i][j], b = cli.rows[i][j];
                if (std::isnan(a) && std::isnan(b)) continue;
                ASSERT_EQ(a, b) << what << ": row " << i << ", " << panel.columns[j];
            }
        }
    }

    fs::path dir_;
    ProjectDocument document_;
};

TEST_F(Equivalence, ForcesAndSoilCurves) {
    ForcesPanel panel(&document_);
    ASSERT_TRUE(test::waitForResult(panel));
    runScript({{"name", "forces"}, {"type", "forces"}, {"plots", {"Fx_N"}}});
    expectSame(panel.result().table, csv("forces.csv"), "forces");
    runScript({{"name", "soil"}, {"type", "soil-curves"}});
    expectSame(panel.soilCurves().bulldozing, csv("soil-bulldozing.csv"), "bulldozing");
    expectSame(panel.soilCurves().static_sinkage, csv("soil-static-sinkage.csv"), "static sinkage");
}

TEST_F(Equivalence, Stresses) {
    StressPanel panel(&document_);
    panel.applySettings({{"slip", 0.25}, {"slip_angle_deg", 8.0}});
    ASSERT_TRUE(test::waitForResult(panel));
    runScript({{"name", "st"}, {"type", "stresses"}, {"slip", 0.25}, {"slip_angle_deg", 8.0}});
    expectSame(panel.result().table, csv("st.csv"), "stresses");
    expectSame(analysis::errorTable(panel.result()), csv("st-errors.csv"), "errors");
}

TEST_F(Equivalence, Sensitivity) {
    SensitivityPanel panel(&document_);
    panel.applySettings({{"parameter", "c_kPa"}, {"slip_angle_deg", 12.0}, {"tornado_slip", 0.4}});
    ASSERT_TRUE(test::waitForResult(panel, 60000));
    runScript({{"name", "c"},
               {"type", "sensitivity"},
               {"parameter", "c_kPa"},
               {"slip_angle_deg", 12.0},
               {"tornado_slip", 0.4}});
    expectSame(panel.result().family.table, csv("c.csv"), "family");
    expectSame(panel.result().tornado, csv("c-tornado.csv"), "tornado");
}

TEST_F(Equivalence, IdentificationWithRefinement) {
    IdentificationPanel panel(&document_);  // synthetic at ½W, W, 1½W, 2 % noise, refined
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const analysis::IdentificationSettings s = panel.fitSettings();
    runScript({{"name", "id"},
               {"type", "identification"},
               {"loads_N", s.synthetic.loads_n},
               {"noise_percent", s.synthetic.noise_percent},
               {"refine", s.refine}});
    expectSame(panel.result().parameters, csv("id-parameters.csv"), "parameters");
    expectSame(panel.result().curves, csv("id.csv"), "curves");
}

TEST_F(Equivalence, StreamingPlayback) {
    IdentificationPanel panel(&document_);
    panel.showPage(1);
    panel.setStreamSource("", "clayey-soil");
    panel.setStreamSpeed(0.0);  // as fast as it computes
    QSignalSpy ended(&panel, &IdentificationPanel::playbackEnded);
    panel.play();
    ASSERT_TRUE(ended.wait(120000));
    ASSERT_EQ(panel.playback().state(), StreamingPlayback::State::kFinished);
    const analysis::StreamingSettings s = panel.streamSettings();
    runScript({{"name", "stream"},
               {"type", "streaming"},
               {"second_soil", s.second_soil},
               {"noise_percent", s.noise_percent}});
    expectSame(panel.currentTable(), csv("stream.csv"), "frames");
}

TEST_F(Equivalence, RoverRun) {
    RoverPanel panel(&document_, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    json scenario = json::parse(panel.scenarioText().toStdString());
    scenario["duration_s"] = 2.0;
    QString error;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(scenario.dump()), &error))
        << error.toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 60000));
    runScript({{"name", "rover"},
               {"type", "rover"},
               {"scenario", "straight"},
               {"duration_s", 2.0},
               {"plots", {"path"}}});
    expectSame(panel.result().series, csv("rover-timeseries.csv"), "time series");
}

}  // namespace
}  // namespace terra::ui
