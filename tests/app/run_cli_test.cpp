// `terrastudio run SCRIPT.json --out DIR` on the real executable: outputs, expectations and exit
// codes (0 all met, 1 an expectation failed, 2 a broken script).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

struct CliResult {
    int exit_code = -1;
    std::string out, err;
};

CliResult terrastudio(const std::string& arguments) {
    const fs::path err_path = fs::temp_directory_path() / ("terra_run_err_" + std::to_string(::getpid()));
    const std::string command = std::string(TERRASTUDIO_EXE) + " " + arguments + " 2>" + err_path.string();
    CliResult r;
    FILE* pipe = ::popen(command.c_str(), "r");
    std::array<char, 4096> buffer{};
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.out.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream err(err_path);
    r.err.assign(std::istreambuf_iterator<char>(err), {});
    fs::remove(err_path);
    return r;
}

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
}

class RunCommand : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("terra_run_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path writeScript(const nlohmann::json& script) {
        const fs::path path = dir_ / "script.json";
        std::ofstream(path) << script.dump(2);
        return path;
    }
    fs::path dir_;
};

// F_x at s = 0.3, β = 5° from the single-point `wheel` command: an independent path through the CLI.
double singlePointFx() {
    const CliResult r = terrastudio("wheel --soil sandy-loam --wheel A --slip 0.3 --slip-angle 5 --load 58.86 --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["Fx_N"].get<double>();
}

nlohmann::json forcesScript(double low, double high) {
    return {{"title", "test"},
            {"soil", "sandy-loam"},
            {"wheel", "A"},
            {"conditions", {{"load_N", 58.86}, {"slip_angles_deg", {5, 15}}, {"slip_count", 100}, {"slip_max", 0.99}}},
            {"export", {{"width", 640}, {"height", 480}, {"formats", {"png", "svg"}}}},
            {"analyses",
             {{{"name", "fx"},
               {"type", "forces"},
               {"plots", {"Fx_N"}},
               {"expect", {{{"column", "Fx_N"}, {"at", {{"slip", 0.3}, {"slip_angle_deg", 5}}}, {"min", low}, {"max", high}}}}}}}};
}

TEST_F(RunCommand, MetExpectationsExitZeroAndWritePlotsDataReport) {
    const double fx = singlePointFx();
    const fs::path script = writeScript(forcesScript(fx - 1e-6, fx + 1e-6));
    const CliResult r = terrastudio("run " + script.string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    for (const char* file : {"fx-Fx_N.png", "fx-Fx_N.svg", "fx.csv", "report.md", "manifest.json"}) {
        EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
    }
    const std::string report = readText(dir_ / "out" / "report.md");
    EXPECT_NE(report.find("All expectations met"), std::string::npos) << report;
    EXPECT_NE(report.find("![fx-Fx_N.png](fx-Fx_N.png)"), std::string::npos);
    const auto manifest = nlohmann::json::parse(readText(dir_ / "out" / "manifest.json"));
    EXPECT_EQ(manifest["failed"], 0);
    EXPECT_EQ(manifest["inputs"]["soil"], "sandy-loam");
}

TEST_F(RunCommand, FailedExpectationExitsOneAndIsListedInTheReport) {
    const fs::path script = writeScript(forcesScript(1000.0, 2000.0));
    const CliResult r = terrastudio("run " + script.string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.out.find("FAIL: fx: Fx_N at slip = 0.3"), std::string::npos) << r.out;
    const std::string report = readText(dir_ / "out" / "report.md");
    EXPECT_NE(report.find("## Failures"), std::string::npos) << report;
    EXPECT_NE(report.find("NOT in [1000, 2000]"), std::string::npos) << report;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "fx-Fx_N.png"));  // outputs are still written
}

TEST_F(RunCommand, BrokenScriptExitsTwoNamingTheField) {
    nlohmann::json script = forcesScript(0, 1);
    script["analyses"][0]["type"] = "forcez";
    const CliResult bad_type = terrastudio("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(bad_type.exit_code, 2);
    EXPECT_NE(bad_type.err.find("analyses[0].type"), std::string::npos) << bad_type.err;

    script = forcesScript(0, 1);
    script["set"] = {{"phi_deg", 75}};
    const CliResult bad_value = terrastudio("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(bad_value.exit_code, 2);
    EXPECT_NE(bad_value.err.find("phi_deg"), std::string::npos) << bad_value.err;
    EXPECT_NE(bad_value.err.find("[0, 60)"), std::string::npos) << bad_value.err;

    const CliResult missing = terrastudio("run " + (dir_ / "nope.json").string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(missing.exit_code, 2);
}

TEST_F(RunCommand, ShippedExampleScriptsRunAndMeetTheirExpectations) {
    for (const auto& entry : fs::directory_iterator(TERRA_RESOURCE_DIR "/scripts")) {
        if (entry.path().extension() != ".json") continue;
        const fs::path out = dir_ / entry.path().stem();
        const CliResult r = terrastudio("run " + entry.path().string() + " --out " + out.string());
        EXPECT_EQ(r.exit_code, 0) << entry.path() << "\n" << r.err << r.out;
        EXPECT_TRUE(fs::exists(out / "report.md")) << entry.path();
    }
}

}  // namespace
