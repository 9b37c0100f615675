#include "core/io/field_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/io/raster_io.h"
#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

const PresetLocations kPresets{{TERRA_RESOURCE_DIR}};

void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

// The shipped sloped field: its slope is the 8 % and 3 % the generator wrote (away from the
// hollow), the hollow's soil is the wet clay preset with its profile, and the headlands' soil
// carries the dry profile.
TEST(FieldJson, ShippedSlopedFieldReadsAsWritten) {
    Result<FieldFile> f = loadField(
        std::filesystem::path(TERRA_RESOURCE_DIR) / "fields/sloped-wet/field.json", kPresets);
    ASSERT_TRUE(f) << f.message();
    const field::FieldMap& map = f->map;
    const Eigen::Vector2d g = map.gradientAt(10.3, 5.2);
    EXPECT_NEAR(g.x(), 0.08, 1e-9);
    EXPECT_NEAR(g.y(), 0.03, 1e-9);
    EXPECT_NEAR(map.heightAt(10.25, 5.25), 100.0 + 0.08 * 10.25 + 0.03 * 5.25, 1e-4);
    // The hollow's bottom lies 0.3 m below the plane.
    EXPECT_NEAR(map.heightAt(32.0, 22.0) - (100.0 + 0.08 * 32.0 + 0.03 * 22.0), -0.3, 0.01);
    Result<soil::SoilParameters> wet = resolveSoil(kPresets, "lean-clay-wet");
    ASSERT_TRUE(wet);
    const soil::SoilParameters hollow = map.soilAt(32.0, 22.0);
    EXPECT_EQ(hollow.name, wet->name);
    EXPECT_DOUBLE_EQ(hollow.cohesion_pa, wet->cohesion_pa);
    ASSERT_TRUE(hollow.profile);
    EXPECT_EQ(hollow.profile->name, resolveProfile(kPresets, "clay-wet")->name);
    EXPECT_EQ(f->labels.at(3), "headland");
    EXPECT_EQ(map.classAt(3.0, 20.0), 3);
    EXPECT_EQ(map.classAt(20.0, 20.0), 1);
}

TEST(FieldJson, ShippedControlledTrafficFieldHasItsLanes) {
    Result<FieldFile> f = loadField(
        std::filesystem::path(TERRA_RESOURCE_DIR) / "fields/controlled-traffic/field.json",
        kPresets);
    ASSERT_TRUE(f) << f.message();
    for (double y : {0.1, 3.3, 6.5, 27.1}) EXPECT_EQ(f->map.classAt(17.0, y), 2) << y;
    for (double y : {0.7, 2.9, 4.0, 29.9}) EXPECT_EQ(f->map.classAt(17.0, y), 1) << y;
    EXPECT_EQ(f->map.heightAt(17.0, 3.0), 0.0);
}

TEST(FieldJson, RastersBesideTheFileAndParameterRasters) {
    testing::TempDir temp;
    write(temp.path() / "c.asc", "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 5\n1 1\n");
    write(temp.path() / "phi.csv", "x_m,y_m,phi_deg\n7.5,2.5,24\n");
    write(temp.path() / "f.json",
          R"({"soil": "sandy-loam", "soil_classes": "c.asc", "legend": {"1": "dry-sand"},
              "parameters": {"phi_deg": "phi.csv"}})");
    Result<FieldFile> f = loadField(temp.path() / "f.json", kPresets);
    ASSERT_TRUE(f) << f.message();
    EXPECT_EQ(f->map.soilAt(2.5, 2.5).name, resolveSoil(kPresets, "dry-sand")->name);
    EXPECT_NEAR(f->map.soilAt(7.5, 2.5).friction_angle_rad, 24.0 * M_PI / 180.0, 1e-12);
    EXPECT_EQ(f->map.soilAt(-1.0, 2.5).name, resolveSoil(kPresets, "sandy-loam")->name);
}

TEST(FieldJson, ProblemsNameTheKeyAndTheClass) {
    testing::TempDir temp;
    write(temp.path() / "c.asc", "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 4 4\n");
    write(temp.path() / "f.json",
          R"({"soil": "sandy-loam", "soil_classes": "c.asc", "legend": {"1": "dry-sand"}})");
    Result<FieldFile> missing_class = loadField(temp.path() / "f.json", kPresets);
    ASSERT_FALSE(missing_class);
    EXPECT_NE(
        missing_class.message().find("soil_classes: class 4 (2 cells) has no entry in the legend"),
        std::string::npos)
        << missing_class.message();

    write(temp.path() / "g.json",
          R"({"soil": "sandy-loam", "hieght": "h.asc", "parameters": {"phi": "c.asc"},
              "legend": {"x": "dry-sand"}})");
    Result<FieldFile> bad = loadField(temp.path() / "g.json", kPresets);
    ASSERT_FALSE(bad);
    const std::string m = bad.message();
    EXPECT_NE(m.find("parameters.phi: is not a soil parameter (did you mean 'phi_deg'?)"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("hieght"), std::string::npos) << m;
    EXPECT_NE(m.find("height"), std::string::npos) << m;  // the suggestion
    EXPECT_NE(m.find("legend.x: a class code must be a whole number"), std::string::npos) << m;

    write(temp.path() / "h.json", R"({"soil": "sandy-loam", "height": "nowhere.asc"})");
    Result<FieldFile> no_file = loadField(temp.path() / "h.json", kPresets);
    ASSERT_FALSE(no_file);
    EXPECT_NE(no_file.message().find("nowhere.asc"), std::string::npos) << no_file.message();
}

}  // namespace
}  // namespace terra::io
