// The posterior carried on (issue 25, item 4), on the real executable: `identify --save-soil`
// writes the identified soil with its posterior, and `traction`, `bands` and `gsa --posterior`
// sample from it with its correlations; a band from it against one from independent normals of
// the same std (docs/identification.md, "The posterior carried on").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

using nlohmann::json;
using terra::test::CliRun;
using terra::test::run;

class PosteriorCli : public ::testing::Test {
protected:
    // The README tour's data (sandy loam, three loads, 1 % noise) identified with the soil's
    // j_max, saved with its posterior; the path of the soil file.
    std::string identified() {
        const std::string data = (dir_ / "tour.csv").string();
        const std::string soil = (dir_ / "identified.json").string();
        CliRun r =
            run("synth --soil sandy-loam --wheel A --load 30,58.86,90 "
                "--noise fx=1%,fz=1%,my=1% --out " +
                data);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        r = run("identify --data " + data + " --wheel A --jmax 0.02 --refine --save-soil " + soil);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return soil;
    }

    terra::testing::TempDir temp_;
    const std::filesystem::path dir_ = temp_.path();
};

json readJson(const std::string& path) {
    std::ifstream in(path);
    return json::parse(in);
}

// The 2.5 % and 97.5 % percentiles of F_x at s = 0.3 from `bands ARGUMENTS`.
std::pair<double, double> band(const std::string& arguments) {
    const CliRun r =
        run("bands --wheel A --slip 0.3 --outputs Fx_N --percentiles 2.5,97.5 "
            "--samples 1000 --json " +
            arguments);
    EXPECT_EQ(r.exit_code, 0) << arguments << "\n" << r.err;
    if (r.exit_code != 0) return {NAN, NAN};
    const json row = json::parse(r.out)["rows"].at(0);
    return {row["Fx_N_p2.5"].get<double>(), row["Fx_N_p97.5"].get<double>()};
}

TEST_F(PosteriorCli, ABandFromTheIdentifiedSoilKeepsItsCorrelations) {
    const std::string soil = identified();
    const json posterior = readJson(soil)["posterior"];
    // The same std, correlations dropped: independent normals (truncated to the fields' ranges,
    // where a draw would be no soil).
    std::string normals;
    // The posterior names K_s and n₀ as the identification does; --normal takes soil keys.
    std::vector<std::string> keys = posterior["parameters"].get<std::vector<std::string>>();
    for (std::string& key : keys) key = key == "Ks_kPa" ? "kphi" : key == "n0" ? "n" : key;
    const std::vector<std::pair<double, double>> ranges{
        {0.0, 1.0}, {-1.0, 1.0}, {0.0, 1e5}, {0.1, 2.0}, {0.0, 200.0}, {0.0, 59.0}, {1e-4, 0.5}};
    ASSERT_EQ(keys.size(), ranges.size());
    for (std::size_t k = 0; k < keys.size(); ++k) {
        const double sd = std::sqrt(posterior["covariance"][k][k].get<double>());
        char item[200];
        std::snprintf(item, sizeof item, " --normal %s=%.17g,%.17g,%g:%g", keys[k].c_str(),
                      posterior["mean"][k].get<double>(), sd, ranges[k].first, ranges[k].second);
        normals += item;
    }
    const auto [low, high] = band("--posterior " + soil);
    const auto [independent_low, independent_high] =
        band("--soil " + soil + normals + " --max-failed-fraction 1");
    std::printf(
        "95 %% band of Fx at s = 0.3: posterior [%.3f, %.3f] N, independent [%.3f, %.3f] N\n", low,
        high, independent_low, independent_high);
    // The identified soil's own F_x lies in its band.
    const CliRun wheel = run("wheel --soil " + soil + " --wheel A --load 58.86 --slip 0.3 --json");
    ASSERT_EQ(wheel.exit_code, 0) << wheel.err;
    const double fx = json::parse(wheel.out)["Fx_N"].get<double>();
    EXPECT_LT(low, fx);
    EXPECT_GT(high, fx);
    // The correlations (c–φ, K_s–n) cancel most of the spread the std alone imply.
    EXPECT_LT(high - low, 0.2 * (independent_high - independent_low));
}

TEST_F(PosteriorCli, TractionBandsAndGsaReadTheSavedPosterior) {
    const std::string soil = identified();
    CliRun r = run("traction --posterior " + soil + " --wheel A --samples 20 --model quadratic");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("robust s*"), std::string::npos) << r.out;
    // Without --soil the posterior's file is the soil: its name heads the output.
    EXPECT_NE(r.out.find("identified from tour.csv"), std::string::npos) << r.out;
    r = run("gsa --posterior " + soil +
            " --wheel A --slip 0.3 --samples 64 --resamples 0 --model quadratic --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out)["parameters"].get<std::vector<std::string>>(),
              (std::vector<std::string>{"a0", "a1", "kphi", "n", "c_kPa", "phi_deg", "K_m"}));
    // With an independent parameter beside it (a key the posterior does not hold).
    r = run("bands --posterior " + soil + " --normal gamma_kN_m3=15,1 --slip 0.3 --samples 50");
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(PosteriorCli, AParameterGivenTwiceOrAMorrisStudyIsRefused) {
    const std::string soil = identified();
    CliRun r = run("bands --posterior " + soil + " --normal phi_deg=29,1 --samples 50");
    EXPECT_EQ(r.exit_code, 2);
    // The reader's words (issue 26), named by the flag that gave the key the second time.
    EXPECT_NE(r.err.find("--posterior '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(": \"phi_deg\" is varied twice"), std::string::npos) << r.err;
    r = run("gsa --method morris --posterior " + soil);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--posterior"), std::string::npos) << r.err;
    r = run("bands --posterior /no/such/posterior.json --samples 50");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--posterior"), std::string::npos) << r.err;
    // A soil file without a posterior is named as such.
    r = run("bands --posterior " + std::string(TERRA_RESOURCE_DIR) +
            "/soils/sandy-loam.json --samples 50");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("parameters"), std::string::npos) << r.err;
}

// A posterior with the identification's old key "Ks" (issue 26) is read as Ks_kPa, k_phi in the
// soil, with the deprecation note the flags give — by traction's notes and bands' warnings — and
// samples the same soils as one written with the new key.
TEST_F(PosteriorCli, AnOldParameterKeyInAPosteriorIsReadWithTheFlagsNote) {
    auto write = [&](const std::string& name, const char* ks_key) {
        const std::string path = (dir_ / name).string();
        std::ofstream(path) << json{{"parameters", {"phi_deg", ks_key}},
                                    {"mean", {29.0, 1500.0}},
                                    {"covariance", {{1.0, 0.0}, {0.0, 400.0}}}}
                                   .dump();
        return path;
    };
    const std::string old_file = write("old.json", "Ks"), new_file = write("new.json", "Ks_kPa");
    const std::string traction =
        "traction --soil sandy-loam --wheel A --samples 20 --model quadratic --json --posterior ";
    const CliRun old_run = run(traction + old_file), new_run = run(traction + new_file);
    ASSERT_EQ(old_run.exit_code, 0) << old_run.err;
    ASSERT_EQ(new_run.exit_code, 0) << new_run.err;
    EXPECT_NE(old_run.err.find("parameter key 'Ks' is deprecated: use 'Ks_kPa'"), std::string::npos)
        << old_run.err;
    EXPECT_EQ(new_run.err.find("deprecated"), std::string::npos) << new_run.err;
    json a = json::parse(old_run.out), b = json::parse(new_run.out);
    EXPECT_EQ(a["robust_slip"], b["robust_slip"]);
    const std::string bands =
        "bands --soil sandy-loam --wheel A --slip 0.3 --samples 50 --posterior ";
    const CliRun old_bands = run(bands + old_file);
    ASSERT_EQ(old_bands.exit_code, 0) << old_bands.err;
    EXPECT_NE(old_bands.err.find("warning: --posterior"), std::string::npos) << old_bands.err;
    EXPECT_NE(old_bands.err.find("'Ks' is deprecated"), std::string::npos) << old_bands.err;
    EXPECT_EQ(old_bands.out, run(bands + new_file).out);
}

}  // namespace
