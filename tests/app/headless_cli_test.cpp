// Headless hygiene of the real executable: `--version` is CMake's project version, and a
// successful `run` or `render` prints nothing on stderr (Qt's "XDG_RUNTIME_DIR not set" warning
// included) and leaves nothing behind in the temporary folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using terra::test::CliRun;
using terra::test::run;

const std::string kVersionLine = std::string("terrastudio ") + TERRA_PROJECT_VERSION;

// Sets (or, with no value, unsets) an environment variable of this process and so of the
// executable it starts; the old value comes back at the end of the scope.
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const std::optional<std::string>& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value)
            ::setenv(name, value->c_str(), 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnvironment() {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

// A run with no XDG_RUNTIME_DIR (as on a CI machine) and a temporary folder of its own.
class HeadlessRun : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("terra_headless_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "tmp");
        tmpdir_.emplace("TMPDIR", (dir_ / "tmp").string());
        runtime_.emplace("XDG_RUNTIME_DIR", std::nullopt);
    }
    void TearDown() override {
        runtime_.reset();
        tmpdir_.reset();
        fs::remove_all(dir_);
    }
    bool temporaryFolderIsEmpty() const { return fs::is_empty(dir_ / "tmp"); }
    fs::path dir_;
    std::optional<ScopedEnvironment> tmpdir_;
    std::optional<ScopedEnvironment> runtime_;
};

TEST(Headless, VersionIsTheProjectVersion) {
    const CliRun r = run("--version");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, kVersionLine + "\n");
    EXPECT_EQ(r.err, "");
}

TEST_F(HeadlessRun, SuccessfulRunPrintsNothingOnStderr) {
    const nlohmann::json script = {
        {"title", "stderr check"},
        {"soil", "sandy-loam"},
        {"wheel", "A"},
        {"conditions",
         {{"load_N", 58.86}, {"slip_angles_deg", {5}}, {"slip_count", 10}, {"slip_max", 0.9}}},
        {"export", {{"width", 320}, {"height", 240}, {"formats", {"png"}}}},
        {"analyses",
         {{{"name", "fx"}, {"type", "forces"}, {"plots", {"Fx_N"}}},
          {{"name", "stresses"}, {"type", "stresses"}, {"slip", 0.2}, {"slip_angle_deg", 10}}}}};
    std::ofstream(dir_ / "script.json") << script.dump(2);
    const CliRun r =
        run("run " + (dir_ / "script.json").string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("wrote " + (dir_ / "out" / "report.md").string()), std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "fx-Fx_N.png"));
    std::ifstream manifest_file(dir_ / "out" / "manifest.json");
    const auto manifest = nlohmann::json::parse(manifest_file);
    EXPECT_EQ(manifest["tool"], kVersionLine);
    EXPECT_TRUE(temporaryFolderIsEmpty());  // the private runtime folder is gone
}

TEST_F(HeadlessRun, SuccessfulRenderPrintsNothingOnStderr) {
    const CliRun r = run("render --soil sandy-loam --wheel A --width 320 --height 240 --out " +
                         (dir_ / "render").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(fs::exists(dir_ / "render" / "forces-vs-slip.csv"));
    EXPECT_TRUE(temporaryFolderIsEmpty());
}

}  // namespace
