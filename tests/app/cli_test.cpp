// The real `terrastudio` executable on good and bad inputs: exit codes, messages and output.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

using terra::test::CliRun;
using terra::test::run;

std::string data(const std::string& name) { return std::string(TERRA_TEST_DATA_DIR) + "/" + name; }

TEST(Cli, WheelJsonHasTheDocumentedKeys) {
    const CliRun r =
        run("wheel --soil sandy-loam --wheel A --slip 0.3 --slip-angle 15 --load 58.86 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm", "Mz_Nm", "Fb_N", "Fs_N",
                            "entry_angle_deg", "sinkage_m"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_NEAR(j["Fz_N"].get<double>(), 58.86, 1e-8);  // the entry angle carries the load
    const double theta = j["entry_angle_deg"].get<double>() * M_PI / 180;
    EXPECT_NEAR(j["sinkage_m"].get<double>(), 0.092 * (1 - std::cos(theta)), 1e-12);
}

TEST(Cli, Table23FlagsOverrideTheSoilFile) {
    // θ_m fixed at 15° and no j_max: the vertical force differs from the default soil file's.
    const CliRun table =
        run("wheel --soil sandy-loam --wheel A --slip 0.3 --slip-angle 12 --entry-angle 30 "
            "--max-stress-angle 15 --no-jmax --json");
    const CliRun plain =
        run("wheel --soil sandy-loam --wheel A --slip 0.3 --slip-angle 12 --entry-angle 30 --json");
    ASSERT_EQ(table.exit_code, 0) << table.err;
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_NE(nlohmann::json::parse(table.out)["Fz_N"], nlohmann::json::parse(plain.out)["Fz_N"]);
}

TEST(Cli, HumanTableNamesEveryForce) {
    const CliRun r = run("wheel --soil clayey-soil --wheel B --slip 0.2 --entry-angle 20");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* name : {"Fx", "Fy", "Fz", "Mx", "My", "Mz", "Fb", "Fs"}) {
        EXPECT_NE(r.out.find(name), std::string::npos) << name;
    }
}

TEST(Cli, BadInputExitsTwoAndNamesTheProblem) {
    struct Case {
        std::string args;
        std::string expected;
    } cases[] = {
        {"wheel --soil sandy-loam --wheel A --slip 1.5 --load 50", "slip"},
        {"wheel --soil nowhere --wheel A --load 50", "nowhere"},
        {"wheel --soil sandy-loam --wheel A --set phi_deg=75 --load 50", "phi_deg"},
        {"wheel --soil sandy-loam --wheel A --slip 0.2", "--entry-angle"},
        {"wheel --soil sandy-loam --wheel A --entry-angle 120", "entry_angle_deg"},
        {"wheel --soil sandy-loam --wheel A --entry-angle 30 --load 50", "excludes"},
        {"wheel --soil sandy-loam --wheel A --entry-angle 30 --model cubic", "model"},
        {"sweep --soil sandy-loam --slips 0:1.1:12",
         "--slips[11]: 1.1 is outside the allowed range [-1, 1]"},
        {"sensitivity --parameter phi_deg --values 20,70", "phi_deg"},
        {"wheel --bogus", "bogus"},
    };
    for (const Case& c : cases) {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
    }
}

TEST(Cli, NoEquilibriumExitsOneAndSaysWhy) {
    const CliRun r = run("wheel --soil dry-sand --wheel A --load 5000");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("axle"), std::string::npos) << r.err;
}

TEST(Cli, BatchModeWritesOneRowPerPoint) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_batch_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream in(dir / "points.csv");
        in << "slip,slip_angle_deg,load_N\n0.1,5,58.86\n0.3,15,40\n-0.2,0,58.86\n";
    }
    const CliRun r = run("wheel --soil sandy-loam --wheel A --input " +
                         (dir / "points.csv").string() + " --output " + (dir / "out.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream out(dir / "out.csv");
    std::string header, line;
    std::getline(out, header);
    EXPECT_NE(header.find("Fx_N"), std::string::npos);
    int rows = 0;
    while (std::getline(out, line)) {
        ++rows;
        EXPECT_NE(line.find(",ok,"), std::string::npos) << line;
    }
    EXPECT_EQ(rows, 3);

    // A bad row is reported with its line number and nothing is written.
    {
        std::ofstream in(dir / "bad.csv");
        in << "slip,entry_angle_deg\n0.1,20\n0.2,abc\n";
    }
    const CliRun bad =
        run("wheel --soil sandy-loam --wheel A --input " + (dir / "bad.csv").string() +
            " --output " + (dir / "bad-out.csv").string());
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("bad.csv:3"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad-out.csv"));
    std::filesystem::remove_all(dir);
}

TEST(Cli, SweepAndSensitivityProduceTables) {
    const CliRun sweep =
        run("sweep --soil sandy-loam --wheel A --slips 0:0.9:10 --slip-angles 5,15 --json");
    ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
    EXPECT_EQ(nlohmann::json::parse(sweep.out)["rows"].size(), 20u);
    const CliRun sens =
        run("sensitivity --soil sandy-loam --wheel A --parameter K_m --slips 0.2,0.5");
    ASSERT_EQ(sens.exit_code, 0) << sens.err;
    EXPECT_EQ(sens.out.rfind("K_m,", 0), 0u) << sens.out.substr(0, 80);
    const CliRun sinkage = run("sinkage --soil clayey-soil --wheel A --load 25,58.86,98 --json");
    ASSERT_EQ(sinkage.exit_code, 0) << sinkage.err;
    EXPECT_EQ(nlohmann::json::parse(sinkage.out).size(), 3u);
}

TEST(Cli, PresetsListsTheThesisSoilsAndWheels) {
    const CliRun r = run("presets --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    std::vector<std::string> soils;
    for (const auto& s : j["soils"]) soils.push_back(s["preset"]);
    for (const char* name : {"dry-sand", "sandy-loam", "clayey-soil", "lete-sand"}) {
        EXPECT_NE(std::find(soils.begin(), soils.end(), name), soils.end()) << name;
    }
    // The thesis's wheels A and B (Table 5.1), beside any other shipped wheel (the Ding 2011
    // rig's).
    std::vector<std::string> wheels;
    for (const auto& w : j["wheels"]) wheels.push_back(w["preset"]);
    for (const char* name : {"A", "B"}) {
        EXPECT_NE(std::find(wheels.begin(), wheels.end(), name), wheels.end()) << name;
    }
}

TEST(Cli, BadFixtureFilesNameTheField) {
    const CliRun phi =
        run("wheel --soil " + data("bad/soil-phi-out-of-range.json") + " --wheel A --load 50");
    EXPECT_EQ(phi.exit_code, 2);
    EXPECT_NE(phi.err.find("phi_deg"), std::string::npos) << phi.err;
    const CliRun json =
        run("wheel --soil " + data("bad/soil-not-json.json") + " --wheel A --load 50");
    EXPECT_EQ(json.exit_code, 2);
    EXPECT_NE(json.err.find("invalid JSON"), std::string::npos) << json.err;
    const CliRun wheel = run("wheel --soil sandy-loam --wheel " +
                             data("bad/wheel-negative-radius.json") + " --load 50");
    EXPECT_EQ(wheel.exit_code, 2);
    EXPECT_NE(wheel.err.find("r_m"), std::string::npos) << wheel.err;
    const CliRun good =
        run("wheel --soil " + data("good/soil-custom.json") + " --wheel A --load 50 --json");
    EXPECT_EQ(good.exit_code, 0) << good.err;
}

TEST(Cli, BatchSkipsShortAndBadRowsOnRequest) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_skip_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream in(dir / "mixed.csv");
        in << "slip,entry_angle_deg,rut_ratio\n0.1,20,0\n0.2\n0.3,25,1.5\n0.4,30,0.5\n";
    }
    const std::string args = "wheel --soil sandy-loam --wheel A --input " +
                             (dir / "mixed.csv").string() + " --output " +
                             (dir / "out.csv").string();
    const CliRun strict = run(args);
    EXPECT_EQ(strict.exit_code, 2);
    EXPECT_NE(strict.err.find("mixed.csv:3"), std::string::npos) << strict.err;  // short row
    EXPECT_NE(strict.err.find("rut_ratio"), std::string::npos) << strict.err;    // 1.5 > 1
    EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
    const CliRun skip = run(args + " --skip-bad-rows");
    ASSERT_EQ(skip.exit_code, 0) << skip.err;
    std::ifstream out(dir / "out.csv");
    int lines = 0;
    for (std::string line; std::getline(out, line);) ++lines;
    EXPECT_EQ(lines, 3);  // header + the two good rows
    std::filesystem::remove_all(dir);
}

TEST(Cli, BareNamesArePresetsEvenWithAFileOfThatName) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_shadow_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "A") << "not json";
    const CliRun r = run("wheel --soil sandy-loam --wheel A --entry-angle 20 --json 2>&1; cd " +
                         dir.string() + " && " + TERRASTUDIO_EXE +
                         " wheel --soil sandy-loam --wheel A --entry-angle 20 --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::filesystem::remove_all(dir);
}

TEST(Cli, BatchOnlyFlagsNeedInput) {
    const CliRun r = run("wheel --soil sandy-loam --wheel A --load 50 --output x.csv");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--input"), std::string::npos) << r.err;
}

TEST(Cli, StressesReproduceTable24) {
    // Table 2.3 conditions (s = 0.3 and β = 12° are the defaults; θ_f = 30° given), θ_m = 15°, no
    // j_max, 0.01° grid (docs/model.md, Tables 2.4–2.5): sandy loam σ RMSE 2.1623, τ_l RMSE
    // 0.2121 (E11), MAE σ 1.7427 kPa.
    const CliRun r =
        run("stresses --soil sandy-loam --wheel A --entry-angle 30 --max-stress-angle 15 --no-jmax "
            "--json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto e = nlohmann::json::parse(r.out)["errors"];
    EXPECT_NEAR(e["sigma_rmse_kPa"].get<double>(), 2.1623, 0.5e-4);
    EXPECT_NEAR(e["tau_l_rmse_kPa"].get<double>(), 0.2121, 0.5e-4);
    EXPECT_NEAR(e["sigma_mae_kPa"].get<double>(), 1.7427, 0.5e-4);
    EXPECT_EQ(e["points"].get<int>(), 3001);
}

TEST(Cli, SynthThenIdentify) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_ident_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string data = (dir / "data.csv").string();
    const CliRun synth =
        run("synth --soil clayey-soil --wheel A --load 40,80 --slips 0:0.9:30 "
            "--noise fx=0.05,my=1% --seed 3 --out " +
            data);
    ASSERT_EQ(synth.exit_code, 0) << synth.err;
    // The decoupled fit alone (the refinement is the default): the three steps.
    const CliRun fit = run("identify --data " + data + " --wheel A --no-refine --json");
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto j = nlohmann::json::parse(fit.out);
    // The keys of the identified parameters' field table (core/analysis/identified_parameters.h).
    for (const char* key : {"a0", "a1", "Ks_kPa", "n0", "n1", "c_kPa", "phi_deg", "K_m", "steps"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_FALSE(j.contains("std"));
    EXPECT_EQ(j["samples"].get<int>(), 60);
    EXPECT_EQ(j["steps"].size(), 3u);
    const CliRun refined =
        run("identify --data " + data + " --wheel A --jmax 0.009 --fix a0=0.2 --json");
    ASSERT_EQ(refined.exit_code, 0) << refined.err;
    const auto r = nlohmann::json::parse(refined.out);
    EXPECT_EQ(r["a0"].get<double>(), 0.2);
    EXPECT_EQ(r["n1"].get<double>(), 0.0);  // the full model's constant n is n0
    EXPECT_TRUE(r["std"].contains("phi_deg"));
    EXPECT_EQ(r["std"]["a0"].get<double>(), 0.0);  // fixed
    EXPECT_TRUE(r["flags"].is_array());
    EXPECT_EQ(r["steps"].size(), 3u);  // the global fit's screening, descent, refinement
    EXPECT_EQ(run("identify --data " + data + " --no-refine --fix a0=0.2").exit_code,
              2);  // --fix belongs to the refinement
    // A bad row stops the fit with its line number, unless skipped.
    std::ofstream(dir / "bad.csv")
        << "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\n0.1,20,1,50,0.5\n0.2,120,1,50,0.5\n";
    const CliRun bad = run("identify --data " + (dir / "bad.csv").string());
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("bad.csv:3"), std::string::npos) << bad.err;
    const CliRun noise = run("synth --soil sandy-loam --noise fx=-1 --out " + data);
    EXPECT_EQ(noise.exit_code, 2);
    EXPECT_NE(noise.err.find("--noise fx"), std::string::npos) << noise.err;
    std::filesystem::remove_all(dir);
}

TEST(Cli, IdentifyStreamReportsTheSoilBorder) {
    // Sandy loam then clayey soil, one sample per line: the change is found at the first clay
    // sample.
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_stream_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string a = (dir / "a.csv").string(), b = (dir / "b.csv").string();
    ASSERT_EQ(run("synth --soil sandy-loam --slips 0.05:0.9:80 --noise fx=1%,fz=1%,my=1% --seed 1 "
                  "--out " +
                  a)
                  .exit_code,
              0);
    ASSERT_EQ(run("synth --soil clayey-soil --slips 0.05:0.9:80 --noise fx=1%,fz=1%,my=1% --seed 2 "
                  "--out " +
                  b)
                  .exit_code,
              0);
    // Each soil's sweep in a scrambled, fixed order (stride 37, coprime to 80), as a robot's slip
    // wanders: the streaming estimator initialises on its first 30 samples, which a monotone
    // sweep would confine to low slips.
    std::string line;
    std::ofstream both(dir / "ab.csv");
    for (const std::string& file : {a, b}) {
        std::ifstream in(file);
        std::getline(in, line);
        if (file == a) both << line << '\n';
        std::vector<std::string> rows;
        while (std::getline(in, line)) rows.push_back(line);
        for (std::size_t i = 0; i < rows.size(); ++i) both << rows[(i * 37) % rows.size()] << '\n';
    }
    both.close();
    const CliRun r = run("identify --stream " + (dir / "ab.csv").string() + " --wheel A --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream lines(r.out);
    int count = 0;
    std::vector<int> changes;
    while (std::getline(lines, line)) {
        const auto j = nlohmann::json::parse(line);
        EXPECT_EQ(j["sample"].get<int>(), count);
        if (j.contains("change_at")) changes.push_back(j["change_at"].get<int>());
        ++count;
    }
    EXPECT_EQ(count, 160);
    // The streaming estimator places the change at the border (its confirmation comes a few
    // samples later, on the line that carries change_at).
    EXPECT_EQ(changes, std::vector<int>{80});
    EXPECT_EQ(run("identify --stream " + a + " --data " + a).exit_code, 2);  // one or the other
    EXPECT_EQ(run("identify --stream " + a + " --refine").exit_code, 2);
    std::filesystem::remove_all(dir);
}

// Review item 10: output nits, each checked on the real executable.
TEST(Cli, StressesOutDashWritesTheCsvAloneAndStartsAtTheClampedExitAngle) {
    // θ_r = −30° with θ_f = 10°: the model uses θ_r = −θ_f = −10°, so the grid starts there
    // (it started at −30°, with 20 rows of zeros outside the contact).
    const CliRun r =
        run("stresses --soil sandy-loam --wheel A --entry-angle 10 --exit-angle -30 "
            "--step 1 --out -");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("theta_deg,", 0), 0u) << r.out.substr(0, 80);
    EXPECT_EQ(r.out.find("RMSE"), std::string::npos) << "the summary table was mixed into the CSV";
    std::istringstream lines(r.out);
    std::string header, first;
    std::getline(lines, header);
    std::getline(lines, first);
    EXPECT_EQ(first.substr(0, first.find(',')), "-10");
    int rows = 1;
    for (std::string line; std::getline(lines, line);) ++rows;
    EXPECT_EQ(rows, 21);  // −10°, −9°, …, 10°
}

TEST(Cli, StressesJsonToAFileSaysSoAndEchoesTypedAngles) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("terra_stress_" + std::to_string(::getpid()) + ".json");
    const CliRun r =
        run("stresses --soil sandy-loam --wheel A --entry-angle 30 --max-stress-angle 15 --json "
            "--out " +
            path.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("wrote " + path.string()), std::string::npos) << r.err;
    std::ifstream in(path);
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j["errors"]["max_stress_angle_deg"].get<double>(), 15.0);  // not 15.000000000000002
    std::filesystem::remove(path);
    const CliRun sweep =
        run("sweep --soil sandy-loam --wheel A --entry-angle 25 --slips 0.1,0.5 "
            "--slip-angles 5 --json");
    ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
    // A named document: a range-for over parse(...)["rows"] would iterate a destroyed temporary
    // (found by the test suite under ASan, docs/reliability.md).
    const auto document = nlohmann::json::parse(sweep.out);
    for (const auto& row : document["rows"]) {
        EXPECT_EQ(row["entry_angle_deg"].get<double>(), 25.0);  // not 25.000000000000004
    }
}

TEST(Cli, NoNegativeZeroInAnyOutput) {
    // β = 0: F_y = M_x = M_z = 0 exactly, which used to print as -0.0 / -0.0000.
    const CliRun json =
        run("wheel --soil sandy-loam --wheel A --slip -0 --slip-angle 0 --entry-angle 20 --json");
    ASSERT_EQ(json.exit_code, 0) << json.err;
    EXPECT_EQ(json.out.find("-0.0"), std::string::npos) << json.out;
    const auto j = nlohmann::json::parse(json.out);
    EXPECT_FALSE(std::signbit(j["Fy_N"].get<double>()));
    const CliRun human =
        run("wheel --soil sandy-loam --wheel A --slip -0 --slip-angle 0 --entry-angle 20");
    ASSERT_EQ(human.exit_code, 0) << human.err;
    EXPECT_EQ(human.out.find("-0.0000"), std::string::npos) << human.out;
    EXPECT_EQ(human.out.find("s = -0"), std::string::npos) << human.out;
    const CliRun sweep =
        run("sweep --soil sandy-loam --wheel A --slips -0,0.5 --slip-angles 0 --json");
    ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
    EXPECT_EQ(sweep.out.find("-0.0"), std::string::npos) << sweep.out;
    const CliRun csv = run("sweep --soil sandy-loam --wheel A --slips -0,0.5 --slip-angles 0");
    ASSERT_EQ(csv.exit_code, 0) << csv.err;
    EXPECT_EQ(csv.out.find(",-0,"), std::string::npos) << csv.out;
}

TEST(Cli, BatchBadRowsAreListedInLineOrder) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_order_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream in(dir / "rows.csv");
        in << "slip,entry_angle_deg\n0.1,20\n1.5,20\n0.2\n0.2,abc\n";  // lines 3, 4 (short), 5
    }
    const CliRun r =
        run("wheel --soil sandy-loam --wheel A --input " + (dir / "rows.csv").string());
    EXPECT_EQ(r.exit_code, 2);
    const auto at3 = r.err.find("rows.csv:3"), at4 = r.err.find("rows.csv:4"),
               at5 = r.err.find("rows.csv:5");
    ASSERT_NE(at3, std::string::npos) << r.err;
    ASSERT_NE(at4, std::string::npos) << r.err;
    ASSERT_NE(at5, std::string::npos) << r.err;
    EXPECT_LT(at3, at4) << r.err;
    EXPECT_LT(at4, at5) << r.err;
    std::filesystem::remove_all(dir);
}

TEST(Cli, PathsThatDoNotExistAreNamedAsFiles) {
    const CliRun r = run("wheel --soil no/such/soil.json --wheel A --load 50");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("file 'no/such/soil.json' does not exist"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("neither a file nor a preset"), std::string::npos) << r.err;
    const CliRun wheel = run("wheel --soil sandy-loam --wheel missing-wheel.json --load 50");
    EXPECT_EQ(wheel.exit_code, 2);
    EXPECT_NE(wheel.err.find("file 'missing-wheel.json' does not exist"), std::string::npos)
        << wheel.err;
    const CliRun name =
        run("wheel --soil sandy --wheel A --load 50");  // a bare name: presets listed
    EXPECT_NE(name.err.find("neither a file nor a preset"), std::string::npos) << name.err;
}

TEST(Cli, PresetsIndentsEveryLineOfAnInvalidWheel) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_presets_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "wheels");
    std::ofstream(dir / "wheels" / "broken.json") << R"({"name": "broken", "r_m": -1, "b_m": -2})";
    const CliRun r = run("presets > /dev/null; TERRASTUDIO_RESOURCES=" + dir.string() + " " +
                         TERRASTUDIO_EXE + " presets");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto at = r.out.find("  broken: INVALID:\n");
    ASSERT_NE(at, std::string::npos) << r.out;
    std::istringstream rest(r.out.substr(at));
    std::string line;
    std::getline(rest, line);  // "  broken: INVALID:"
    int problems = 0;
    while (std::getline(rest, line) && line.rfind("      ", 0) == 0) ++problems;
    EXPECT_EQ(problems, 2) << r.out.substr(at);  // r_m and b_m, each on its own indented line
    std::filesystem::remove_all(dir);
}

TEST(Cli, RenderRejectsAZeroLoadWithTheRange) {
    const CliRun r =
        run("render --soil sandy-loam --wheel A --load 0 --out /tmp/terra_render_never");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--load: 0 is outside the allowed range [0.01, 1e+05] N"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists("/tmp/terra_render_never"));
}

TEST(Cli, RenderWritesTheDefaultAnalysisHeadlessly) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terra_render_" + std::to_string(::getpid()));
    const CliRun r =
        run("render --soil sandy-loam --wheel A --width 400 --height 300 --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "forces-vs-slip.csv"));
    for (const char* name : {"Fx_N", "Fs_N", "Fz_N", "My_Nm", "Mz_Nm", "entry_angle_deg"}) {
        const auto png = dir / (std::string(name) + "-vs-slip.png");
        EXPECT_TRUE(std::filesystem::exists(png)) << png;
        EXPECT_GT(std::filesystem::file_size(png), 1000u) << png;
    }
    std::filesystem::remove_all(dir);
}

// The flags of sweep, sensitivity, stresses, sinkage, render and wheel become their analysis's
// settings object, read by its own reader (issue 26): the reader's words, named by the flag,
// exit 2.
TEST(Cli, AnalysisFlagsAreReadByTheSettingsReaderAndNamedByTheFlag) {
    struct Case {
        std::string args;
        std::string expected;
    } cases[] = {
        {"sweep --soil sandy-loam --slips 0.1,1.5",
         "--slips[1]: 1.5 is outside the allowed range [-1, 1]"},
        {"sweep --soil sandy-loam --exit-angle 5",
         "--exit-angle: 5 is outside the allowed range [-90, 0] deg"},
        {"sweep --soil sandy-loam --entry-angle 95",
         "--entry-angle: 95 is outside the allowed range (0, 90] deg"},
        {"sensitivity --parameter phi", "--parameter: \"phi\" is not one of"},
        {"sensitivity --parameter phi", "did you mean \"phi_deg\""},
        {"sensitivity --slip-angle 95",
         "--slip-angle[0]: 95 is outside the allowed range (-90, 90) deg"},
        {"sensitivity --parameter phi_deg --values 20,70", "--values[1]: phi_deg = 70 is outside"},
        {"stresses --step 20", "--step: 20 is outside the allowed range [1e-04, 10] deg"},
        {"stresses --slip 1.5", "--slip: 1.5 is outside the allowed range [-1, 1]"},
        {"stresses --rut-ratio 2", "--rut-ratio: 2 is outside the allowed range [0, 1]"},
        {"sinkage --load 40,0", "--load[1]: 0 is outside the allowed range [0.01, 1e+05] N"},
        {"sinkage --slip-angle -90",
         "--slip-angle: -90 is outside the allowed range (-90, 90) deg"},
        {"render --max-stress-angle 95 --out /tmp/terra_render_never",
         "--max-stress-angle: 95 is outside the allowed range [-90, 90] deg"},
        {"wheel --load 50 --exit-angle 1",
         "--exit-angle: 1 is outside the allowed range [-90, 0] deg"},
    };
    for (const Case& c : cases) {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << c.args << "\n" << r.out;
    }
    EXPECT_FALSE(std::filesystem::exists("/tmp/terra_render_never"));
}

}  // namespace
