// The posterior carried on (core/analysis/soil_posterior.h): what `identify --save-soil` writes
// beside the soil is read back in the soil file's keys, its variances those the identification
// reported as std (a second path: toJson's "std"), and a file that cannot be used is named with
// the key at fault.
#include "core/analysis/soil_posterior.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/analysis/identification.h"
#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::TempDir;

TEST(SoilPosterior, TheIdentificationsNamesAreTheSoilsKeys) {
    // K_s is the saved soil's k_phi (k_c = 0), n0 its n; the old keys too (issue 26); every other
    // name is a soil key already.
    const std::pair<const char*, const char*> names[] = {
        {"Ks_kPa", "kphi"},     {"Ks", "kphi"}, {"n0", "n"},          {"n", "n"},  {"a0", "a0"},
        {"phi_deg", "phi_deg"}, {"K_m", "K_m"}, {"jmax_m", "jmax_m"}, {"kc", "kc"}};
    for (const auto& [name, key] : names) EXPECT_EQ(soilKeyOf(name), key) << name;
}

TEST(SoilPosterior, ASavedIdentificationReadsBackInSoilKeysWithItsStd) {
    const Inputs in = terra::testing::sandyLoamOnA();
    IdentificationSettings s;
    s.synthetic.loads_n = {30.0, 58.86, 90.0};
    s.synthetic.slip_count = 15;
    s.synthetic.noise_percent = 1.0;
    const IdentificationResult r = computeIdentification(in, s);
    ASSERT_TRUE(r.usable()) << r.message;
    ASSERT_TRUE(r.report && r.report->uncertainty.computed);
    for (bool at_bound : r.report->at_bound) ASSERT_FALSE(at_bound);  // none held: Σ as it is
    const Result<soil::SoilParameters> soil =
        identifiedSoilFile(r, in.soil, in.wheel, in.soil.max_shear_deformation_m);
    ASSERT_TRUE(soil) << soil.message();
    nlohmann::json file = io::toJson(soil.value());
    file["posterior"] = soilPosteriorJson(r, soil.value(), in.wheel);
    TempDir dir;
    const std::filesystem::path path = dir.path() / "identified.json";
    std::ofstream(path) << file.dump(2);

    EXPECT_TRUE(isSoilFile(path));
    const Result<SoilPosterior> read = readPosteriorFile(path);
    ASSERT_TRUE(read) << read.message();
    const nlohmann::json j = toJson(r);
    // The free parameters, j_max held: the seven of the full model under their soil keys.
    const std::vector<std::string> keys{"a0", "a1", "kphi", "n", "c_kPa", "phi_deg", "K_m"};
    const std::vector<std::string> names{"a0", "a1", "Ks_kPa", "n0", "c_kPa", "phi_deg", "K_m"};
    ASSERT_EQ(read->parameters, keys);
    ASSERT_EQ(read->covariance.size(), keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
        // The mean is the saved soil's value of the key, and the identification's estimate.
        EXPECT_NEAR(read->mean[i], file[keys[i]].get<double>(), 1e-9 * std::abs(read->mean[i]))
            << keys[i];
        EXPECT_NEAR(read->mean[i], j[names[i]].get<double>(), 1e-9 * std::abs(read->mean[i]))
            << keys[i];
        const double sd = j["std"][names[i]].get<double>();
        EXPECT_NEAR(read->covariance[i][i], sd * sd, 1e-9 * sd * sd) << keys[i];
        for (std::size_t k = 0; k < keys.size(); ++k)
            EXPECT_EQ(read->covariance[i][k], read->covariance[k][i]);
    }
}

TEST(SoilPosterior, AFileThatCannotBeUsedIsNamedWithTheKey) {
    TempDir dir;
    const std::filesystem::path missing = dir.path() / "none.json";
    const Result<SoilPosterior> none = readPosteriorFile(missing);
    ASSERT_FALSE(none);
    EXPECT_TRUE(contains(none.message(), missing.string())) << none.message();

    const std::filesystem::path bad = dir.path() / "bad.json";
    std::ofstream(bad) << R"({"parameters": ["phi_deg", "c_kPa"], "mean": [30, 2],
                             "covariance": [[1, 0], "no"]})";
    const Result<SoilPosterior> rows = readPosteriorFile(bad);
    ASSERT_FALSE(rows);
    EXPECT_TRUE(contains(rows.message(), "covariance")) << rows.message();
    EXPECT_TRUE(contains(rows.message(), "row 1 is not an array of numbers")) << rows.message();
    EXPECT_FALSE(isSoilFile(bad));  // a posterior alone is no soil

    const std::filesystem::path short_file = dir.path() / "short.json";
    std::ofstream(short_file)
        << R"({"posterior": {"parameters": ["phi_deg"], "covariance": [[1]]}})";
    const Result<SoilPosterior> no_mean = readPosteriorFile(short_file);
    ASSERT_FALSE(no_mean);
    EXPECT_TRUE(contains(no_mean.message(), "mean")) << no_mean.message();
    EXPECT_TRUE(contains(no_mean.message(), "posterior")) << no_mean.message();
}

}  // namespace
}  // namespace terra::analysis
