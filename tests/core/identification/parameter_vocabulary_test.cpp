// One vocabulary for the identified parameters (issue 26): one field table, the keys of before
// ("Ks", "n") read everywhere a parameter is named as the same parameter with a deprecation
// note, a misspelt key answered with the nearest one, and the converters between a soil, the
// decoupled parameters and the full model's vector round-trip.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/analysis/identification.h"
#include "core/analysis/registry.h"
#include "core/identification/parameters.h"
#include "core/identification/soil_conversion.h"
#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using terra::testing::contains;
using terra::testing::kDeg;
using terra::testing::kLocations;

// The keys of before and the parameters they named (identification's first table: K_s in
// kPa/m^n as "Ks", the full model's constant n as "n"), written out here, not read from the table.
struct OldKey {
    const char* old_key;
    const char* key;
    FullParameter parameter;
    double DecoupledParameters::*member;
};
const OldKey kOldKeys[] = {{"Ks", "Ks_kPa", kKs, &DecoupledParameters::pressure_modulus},
                           {"n", "n0", kN, &DecoupledParameters::n0}};

TEST(ParameterVocabulary, EveryOldKeyNamesTheSameParameterAsItsNewKey) {
    ASSERT_EQ(deprecatedParameterKeys().size(), std::size(kOldKeys));
    for (const OldKey& old : kOldKeys) {
        const ParameterLookup by_old = lookupParameter(old.old_key);
        const ParameterLookup by_new = lookupParameter(old.key);
        ASSERT_TRUE(by_old) << old.old_key;
        ASSERT_TRUE(by_new) << old.key;
        EXPECT_TRUE(by_old.deprecated) << old.old_key;
        EXPECT_FALSE(by_new.deprecated) << old.key;
        EXPECT_EQ(by_old.field, by_new.field) << old.old_key;
        EXPECT_EQ(by_new.field->member, old.member) << old.key;
        EXPECT_EQ(findParameter(old.old_key), old.parameter) << old.old_key;
        EXPECT_EQ(findParameter(old.key), old.parameter) << old.key;
        EXPECT_EQ(std::string(oldKeyOf(*by_new.field)), old.old_key);
        EXPECT_TRUE(contains(deprecationNote(old.old_key), std::string("'") + old.key + "'"));
    }
    // The solver's view is the table: its names are the table's keys, its factors the inverse.
    for (int k = 0; k < kFullParameterCount; ++k) {
        const ParameterField& field = fieldOf(static_cast<FullParameter>(k));
        EXPECT_EQ(std::string(parameterInfo()[k].name), field.key);
        EXPECT_EQ(parameterInfo()[k].to_user * field.to_si, 1.0) << field.key;
        EXPECT_EQ(findParameter(field.key), static_cast<FullParameter>(k)) << field.key;
    }
    // n1 is a field (the decoupled model's) but no parameter of the full model.
    EXPECT_EQ(fullParameterOf(*findParameterField("n1")), std::nullopt);
}

TEST(ParameterVocabulary, AnOldKeyInAPriorGivesTheSamePriorAndANote) {
    for (const auto& [old_item, new_item] :
         {std::pair{"Ks=1500±500", "Ks_kPa=1500±500"}, std::pair{"n=0.7+-0.2", "n0=0.7+-0.2"}}) {
        Priors by_old, by_new;
        std::vector<std::string> old_notes, new_notes;
        EXPECT_TRUE(parsePriorItem(old_item, by_old, &old_notes).empty()) << old_item;
        EXPECT_TRUE(parsePriorItem(new_item, by_new, &new_notes).empty()) << new_item;
        for (int k = 0; k < kFullParameterCount; ++k) {
            ASSERT_EQ(by_old[k].has_value(), by_new[k].has_value()) << old_item << " " << k;
            if (!by_old[k]) continue;
            EXPECT_EQ(by_old[k]->mean, by_new[k]->mean);
            EXPECT_EQ(by_old[k]->std, by_new[k]->std);
        }
        ASSERT_EQ(old_notes.size(), 1u) << old_item;
        EXPECT_TRUE(contains(old_notes[0], "deprecated")) << old_notes[0];
        EXPECT_TRUE(new_notes.empty()) << new_item;
        EXPECT_EQ(canonicalPriorItem(old_item), new_item);
        EXPECT_EQ(canonicalPriorItem(new_item), new_item);
    }
    // In SI: 1500 kPa/m^n, 0.7.
    Priors priors;
    ASSERT_TRUE(parsePriorItem("Ks=1500±500", priors).empty());
    EXPECT_EQ(priors[kKs]->mean, 1.5e6);
    ASSERT_TRUE(parsePriorItem("n=0.7±0.2", priors).empty());
    EXPECT_EQ(priors[kN]->mean, 0.7);
}

TEST(ParameterVocabulary, AMisspeltKeyGetsTheNearestOne) {
    for (const auto& [typed, meant] :
         {std::pair{"Ks_kpa", "Ks_kPa"}, std::pair{"phi", "phi_deg"}, std::pair{"c_kpa", "c_kPa"},
          std::pair{"n00", "n0"}, std::pair{"KS", "Ks_kPa"}}) {
        Priors priors;
        const std::vector<Issue> issues = parsePriorItem(std::string(typed) + "=1±1", priors);
        ASSERT_EQ(issues.size(), 1u) << typed;
        EXPECT_TRUE(contains(issues[0].message, std::string("did you mean '") + meant + "'"))
            << typed << ": " << issues[0].message;
    }
    Priors priors;
    const std::vector<Issue> far = parsePriorItem("porosity=1±1", priors);
    ASSERT_EQ(far.size(), 1u);
    EXPECT_FALSE(contains(far[0].message, "did you mean")) << far[0].message;
    EXPECT_TRUE(contains(far[0].message, "Ks_kPa")) << far[0].message;  // the allowed keys
}

// The settings of a script's identification object and the problems of reading it.
std::pair<analysis::IdentificationSettings, std::vector<Issue>> settingsOfObject(
    const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    analysis::IdentificationSettings s;
    analysis::readIdentificationSettings(r, analysis::ReadContext{&kLocations, {}}, s);
    r.finish();
    return {s, issues};
}

TEST(ParameterVocabulary, TheSettingsReaderTakesOldKeysAsTheNewOnesWithANote) {
    const auto [by_old, old_issues] =
        settingsOfObject({{"fix", {{"Ks", 1200.0}, {"n", 0.8}}}, {"priors", {"Ks=1500±500"}}});
    const auto [by_new, new_issues] = settingsOfObject(
        {{"fix", {{"Ks_kPa", 1200.0}, {"n0", 0.8}}}, {"priors", {"Ks_kPa=1500±500"}}});
    EXPECT_TRUE(old_issues.empty()) << formatIssues(old_issues);
    EXPECT_TRUE(new_issues.empty()) << formatIssues(new_issues);
    EXPECT_EQ(by_old.fixed, by_new.fixed);
    EXPECT_EQ(by_old.prior_items, by_new.prior_items);  // stored under the new key
    EXPECT_EQ(analysis::toJson(by_old), analysis::toJson(by_new));
    ASSERT_EQ(by_old.key_warnings.size(), 3u);  // priors, fix.Ks, fix.n
    for (const Issue& note : by_old.key_warnings) {
        EXPECT_TRUE(contains(note.where, "script.json: analyses[0].")) << note.where;
        EXPECT_TRUE(contains(note.message, "deprecated")) << note.message;
    }
    EXPECT_TRUE(by_new.key_warnings.empty());
    // The refinement holds the same value whichever key named it: 1200 kPa/m^n.
    const wheel::WheelParameters wheel = io::resolveWheel(kLocations, "A").value();
    const IdentifyOptions o =
        analysis::identifyOptions(by_old, wheel, std::numeric_limits<double>::infinity());
    ASSERT_TRUE(o.fixed[kKs].has_value());
    EXPECT_EQ(*o.fixed[kKs], 1.2e6);
    EXPECT_EQ(*o.fixed[kN], 0.8);

    // Both keys of one parameter: one problem; a misspelt key: the nearest one.
    const auto [both, both_issues] = settingsOfObject({{"fix", {{"Ks", 1.0}, {"Ks_kPa", 1.0}}}});
    ASSERT_EQ(both_issues.size(), 1u) << formatIssues(both_issues);
    EXPECT_TRUE(contains(both_issues[0].where, "fix.Ks")) << both_issues[0].where;
    const auto [typo, typo_issues] = settingsOfObject({{"fix", {{"Ks_kpa", 1.0}}}});
    ASSERT_EQ(typo_issues.size(), 1u) << formatIssues(typo_issues);
    EXPECT_TRUE(contains(typo_issues[0].message, "did you mean \"Ks_kPa\"?"))
        << typo_issues[0].message;
}

// Settings built in code (the studio's typed prior items) with an old key: the fit reads it as
// the new one and its warnings give the reader's note, once.
TEST(ParameterVocabulary, SettingsBuiltInCodeWithAnOldKeyFitAsTheNewOneWithTheNote) {
    analysis::IdentificationSettings s;
    s.synthetic.slip_count = 10;
    s.design_points = 4;
    s.prior_items = {"Ks=1500±500"};
    s.fixed = {{"n", 0.7}};
    const analysis::IdentificationResult old =
        analysis::computeIdentification(terra::testing::sandyLoamOnA(), s);
    s.prior_items = {"Ks_kPa=1500±500"};
    s.fixed = {{"n0", 0.7}};
    const analysis::IdentificationResult now =
        analysis::computeIdentification(terra::testing::sandyLoamOnA(), s);
    ASSERT_TRUE(old.usable() && now.usable()) << old.message << now.message;
    EXPECT_EQ(old.identified.pressure_modulus, now.identified.pressure_modulus);
    EXPECT_EQ(old.identified.n0, 0.7);
    EXPECT_EQ(old.warnings, (std::vector<std::string>{
                                "priors: prior 'Ks=1500±500': parameter key 'Ks' is deprecated: "
                                "use 'Ks_kPa'",
                                "fix.n: parameter key 'n' is deprecated: use 'n0'"}));
    EXPECT_TRUE(now.warnings.empty());
}

// Every soil field of `got` within 1e-12 relative of `want`'s.
void expectSoilWithinRoundTrip(const soil::SoilParameters& got, const soil::SoilParameters& want) {
    for (const soil::SoilField& field : soil::soilFields()) {
        const double a = got.*field.member, b = want.*field.member;
        if (std::isinf(b)) {
            EXPECT_EQ(a, b) << field.key;
        } else {
            EXPECT_NEAR(a, b, 1e-12 * std::abs(b)) << want.name << ": " << field.key;
        }
    }
}

TEST(ParameterConverters, SoilToVectorToDecoupledToSoilIsTheSoil) {
    const wheel::WheelParameters wheel = io::resolveWheel(kLocations, "A").value();
    // lete-sand has k_c/b = 953 kPa/m^n beside k_φ = 5301: K_s = k_c/b + k_φ is undone exactly.
    for (const char* name : {"sandy-loam", "lete-sand"}) {
        const soil::SoilParameters soil = io::resolveSoil(kLocations, name).value();
        ASSERT_EQ(soil.sinkage_exponent_slip, 0.0) << name;  // the full model's n is constant
        const ParameterVector v = fromSoil(soil, wheel);
        // The vector, written out from Eq. 2.9 and the soil's members.
        EXPECT_EQ(v[kKs], soil.cohesive_modulus / wheel.width_m + soil.frictional_modulus);
        EXPECT_EQ(v[kN], soil.sinkage_exponent);
        EXPECT_EQ(v[kPhi], soil.friction_angle_rad);
        const DecoupledParameters d = decoupledOf(v);
        EXPECT_EQ(d.n1, 0.0);
        EXPECT_EQ(vectorOf(d), v);
        // Back onto a base whose identified members are all wrong: each must be set.
        soil::SoilParameters base = soil;
        base.max_stress_a0 = base.max_stress_a1 = 0.5;
        base.frictional_modulus = 1.0;
        base.sinkage_exponent = base.sinkage_exponent_slip = 0.3;
        base.cohesion_pa = 99.0;
        base.friction_angle_rad = 10 * kDeg;
        base.shear_modulus_m = 0.3;
        expectSoilWithinRoundTrip(soilOf(base, wheel, d), soil);
        // The decoupled form of the soil itself is the same vector.
        EXPECT_EQ(vectorOf(decoupledOf(soil, wheel)), v);
    }
}

}  // namespace
}  // namespace terra::identification
