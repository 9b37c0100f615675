// The property editors: invalid text is flagged at the field and never reaches the model; valid
// edits go through the document (undoable).
#include <gtest/gtest.h>

#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QRegularExpression>
#include <QSlider>
#include <QTest>
#include <QUndoStack>
#include <cmath>

#include "core/common/units.h"
#include "widgets/editors/project_tree.h"
#include "widgets/editors/property_editors.h"
#include "widgets/editors/validated_spin_box.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

void typeInto(ValidatedSpinBox* box, const QString& text) {
    box->selectAll();
    QTest::keyClicks(box, text);  // keys reach the spin box (its line edit is a proxy)
    QTest::keyClick(box, Qt::Key_Return);
}

TEST(SoilEditor, OutOfRangeTextIsFlaggedAndNeverCommitted) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    ValidatedSpinBox* phi = editor.spinBox("phi_deg");
    ASSERT_NE(phi, nullptr);
    EXPECT_DOUBLE_EQ(phi->maximum(), 59.99);  // [0, 60): the open end is excluded
    const double before = document.project().soil.friction_angle_rad;

    phi->selectAll();
    QTest::keyClicks(phi, "75");
    EXPECT_FALSE(phi->textIsValid());
    EXPECT_TRUE(phi->property("invalidMessage").toString().contains("[0, 60)"));
    QTest::keyClick(phi, Qt::Key_Return);
    EXPECT_TRUE(phi->textIsValid());  // reverted to the committed value
    EXPECT_DOUBLE_EQ(phi->value(), 29.0);
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, before);
    EXPECT_EQ(document.undoStack()->count(), 0);

    typeInto(phi, "33");
    EXPECT_TRUE(phi->textIsValid());
    EXPECT_NEAR(document.project().soil.friction_angle_rad, units::degToRad(33.0), 1e-12);
    EXPECT_EQ(document.undoStack()->count(), 1);
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(phi->value(), 29.0);  // the editor follows the document back
}

// Typing is live but debounced: a settled, valid text reaches the model without Enter, as one
// undo command; the keystrokes before it ("3" of "33") do not.
TEST(SoilEditor, TypedValueReachesTheModelAfterTheDebounceWithoutEnter) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    ValidatedSpinBox* phi = editor.spinBox("phi_deg");
    ASSERT_NE(phi, nullptr);
    const double before = document.project().soil.friction_angle_rad;
    phi->selectAll();
    QTest::keyClicks(phi, "33");  // no Enter, no focus change
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, before);  // not per keystroke
    EXPECT_TRUE(QTest::qWaitFor(
        [&] {
            return std::abs(document.project().soil.friction_angle_rad - units::degToRad(33.0)) <
                   1e-12;
        },
        10 * phi->debounceMs()));
    EXPECT_EQ(document.undoStack()->count(), 1);  // one undo command for the settled edit
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, before);
    EXPECT_DOUBLE_EQ(phi->value(), 29.0);

    // Two settled edits of one field merge into one undo step (the document's merge id).
    phi->selectAll();
    QTest::keyClicks(phi, "31");
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return document.project().soil.friction_angle_rad != before; }, 3000));
    phi->selectAll();
    QTest::keyClicks(phi, "32");
    ASSERT_TRUE(QTest::qWaitFor(
        [&] {
            return std::abs(document.project().soil.friction_angle_rad - units::degToRad(32.0)) <
                   1e-12;
        },
        3000));
    EXPECT_EQ(document.undoStack()->count(), 1);
}

TEST(SoilEditor, InvalidOrIncompleteTypedTextNeverReachesTheModel) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    ValidatedSpinBox* phi = editor.spinBox("phi_deg");
    const double before = document.project().soil.friction_angle_rad;
    phi->selectAll();
    QTest::keyClicks(phi, "75");  // outside [0, 60)
    QTest::qWait(3 * phi->debounceMs());
    EXPECT_FALSE(phi->textIsValid());
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, before);
    EXPECT_EQ(document.undoStack()->count(), 0);

    phi->selectAll();
    QTest::keyClick(phi, Qt::Key_Backspace);  // empty: intermediate, not a value
    QTest::qWait(3 * phi->debounceMs());
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, before);
    EXPECT_EQ(document.undoStack()->count(), 0);

    ValidatedSpinBox* load = nullptr;
    ConditionsEditor conditions(&document);
    conditions.show();
    load = conditions.loadBox();
    load->selectAll();
    // W ≤ 100 kN, contact::loadField()'s range as everywhere (a typed "-" is refused outright).
    QTest::keyClicks(load, "200000");
    QTest::qWait(3 * load->debounceMs());
    EXPECT_DOUBLE_EQ(document.project().conditions.load_n, 58.86);
    EXPECT_EQ(document.undoStack()->count(), 0);
}

// k_φ spans 0–100000 kN/m^(n+2): its slider maps log10(1 + k_φ / 1) linearly over 10000 steps
// (the box shows 0.1, the knee is 10 × that), so 1515 sits at 10000 · log10(1516) / log10(100001).
TEST(SoilEditor, WideRangeSliderIsLogarithmicSmallValuesReachable) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    QSlider* slider = editor.slider("kphi");
    ValidatedSpinBox* box = editor.spinBox("kphi");
    ASSERT_NE(slider, nullptr);
    ASSERT_EQ(slider->maximum(), 10000);
    const int expected =
        static_cast<int>(std::lround(10000.0 * std::log10(1516.0) / std::log10(100001.0)));
    EXPECT_EQ(slider->value(), expected);  // 6361, not 15 of a linear 1000-step slider

    // One step up from sandy loam moves k_φ by ln(10) · 1516 · 5/10000 ≈ 1.7, not 100.
    slider->setValue(expected + 1);
    const double moved = document.project().soil.frictional_modulus / 1e3 - 1515.0;
    EXPECT_GT(moved, 0.5);
    EXPECT_LT(moved, 3.0);
    EXPECT_EQ(document.undoStack()->count(), 1);

    // Small values are reachable: some position gives 0 < k_φ < 1 kN/m^(n+2) in the model.
    bool small = false;
    for (int p = 1; p < 1000 && !small; p += 10) {
        slider->setValue(p);
        const double kphi = document.project().soil.frictional_modulus / 1e3;
        small = kphi > 0.0 && kphi < 1.0;
    }
    EXPECT_TRUE(small);
    slider->setValue(0);
    EXPECT_DOUBLE_EQ(box->value(), 0.0);
    slider->setValue(10000);
    EXPECT_DOUBLE_EQ(box->value(), 1e5);

    // k_c spans −500..5000: negative values stay reachable through the signed log.
    QSlider* kc = editor.slider("kc");
    kc->setValue(100);
    EXPECT_LT(document.project().soil.cohesive_modulus, 0.0);
}

// Slider → spin box → slider settles: the position the editor shows back maps to the same value,
// and a value typed in the box lands within one step of its slider position.
TEST(SoilEditor, SliderAndSpinBoxRoundTrip) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    for (const char* key : {"kphi", "kc", "c_kPa", "phi_deg", "n"}) {
        QSlider* slider = editor.slider(key);
        ValidatedSpinBox* box = editor.spinBox(key);
        const SliderScale scale = SliderScale::forBox(*box);
        const double resolution = std::pow(10.0, -box->decimals());
        for (int p = 0; p <= slider->maximum(); p += slider->maximum() / 20) {
            slider->setValue(p);
            const double value = box->value();
            const int shown = slider->value();  // after the document's refresh
            const int commands = document.undoStack()->count();
            slider->setValue(shown);  // the user lets go where it is shown
            EXPECT_DOUBLE_EQ(box->value(), value) << key << " " << p;
            EXPECT_EQ(document.undoStack()->count(), commands) << key << " " << p;  // no new edit
            EXPECT_NEAR(scale.fromSlider(shown), value, resolution) << key << " " << p;
        }
        for (int p = 1; p < scale.steps; p += 37) {  // the mapping itself is invertible
            EXPECT_EQ(scale.toSlider(scale.fromSlider(p)), p) << key << " " << p;
        }
        // A typed value: the slider moves to it, and its position maps back within one step.
        const double typed =
            std::round((box->minimum() + 0.123 * (box->maximum() - box->minimum())) / resolution) *
            resolution;
        box->setValue(typed);
        const int at = slider->value();
        EXPECT_LE(scale.fromSlider(at - 1), typed) << key;
        EXPECT_GE(scale.fromSlider(at + 1), typed) << key;
    }
}

TEST(SoilEditor, EveryFieldOfTheCoreTableHasAnEditorWithItsRange) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    for (const soil::SoilField& field : soil::soilFields()) {
        ValidatedSpinBox* box = editor.spinBox(field.key);
        ASSERT_NE(box, nullptr) << field.key;
        EXPECT_EQ(box->allowedRange().describe(), field.range.describe()) << field.key;
        EXPECT_TRUE(box->toolTip().contains(QString::fromStdString(field.displayUnit())))
            << field.key;
        EXPECT_TRUE(box->toolTip().contains(QString::fromUtf8(field.label))) << field.key;
    }
}

// Issue 12: every soil parameter's editor — its label, field and slider — says in its tooltip
// what the parameter means, the thesis equation it belongs to, and its unit.
TEST(SoilEditor, EveryParameterTooltipSaysMeaningEquationAndUnit) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    const QRegularExpression equation("Eqs?\\. [0-9]+\\.[0-9]+");
    for (const soil::SoilField& field : soil::soilFields()) {
        const QString tip = editor.spinBox(field.key)->toolTip();
        EXPECT_TRUE(tip.contains(QString::fromUtf8(field.label))) << field.key;
        EXPECT_TRUE(tip.contains(equation)) << field.key << ": " << tip.toStdString();
        const std::string unit = field.displayUnit();
        EXPECT_TRUE(unit.empty() ? tip.contains("Dimensionless")
                                 : tip.contains(QString::fromStdString(unit)))
            << field.key << ": " << tip.toStdString();
        auto* slider =
            editor.findChild<QSlider*>(QString("soil.") + field.key + QString(".slider"));
        ASSERT_NE(slider, nullptr) << field.key;
        EXPECT_EQ(slider->toolTip(), tip) << field.key;
    }
}

TEST(SoilEditor, ChoosingAPresetIsOneUndoableEdit) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    auto* preset = editor.findChild<QComboBox*>();
    ASSERT_NE(preset, nullptr);
    preset->setCurrentIndex(preset->findData("lean-clay"));
    EXPECT_EQ(document.project().soil_preset, "lean-clay");
    const auto clay = io::resolveSoil(test::resources(), "lean-clay");
    ASSERT_TRUE(clay.ok());
    EXPECT_DOUBLE_EQ(document.project().soil.cohesion_pa, clay->cohesion_pa);
    EXPECT_NEAR(editor.spinBox("c_kPa")->value(), clay->cohesion_pa / 1e3, 1e-9);
    EXPECT_EQ(document.undoStack()->count(), 1);
    document.undoStack()->undo();
    EXPECT_EQ(document.project().soil_preset, "sandy-loam");
    EXPECT_EQ(preset->currentData().toString(), "sandy-loam");
}

// Issue 14: the wheel editor has every field of the wheel's table, the grousers and λ_s with them
// (it used to show r and b only, so a lugged wheel could not be described in the studio).
TEST(WheelEditor, EveryFieldOfTheCoreTableHasAnEditorWithItsRange) {
    ProjectDocument document;
    test::resetToDefault(document);
    WheelEditor editor(&document, test::resources());
    for (const wheel::WheelField& field : wheel::wheelFields()) {
        ValidatedSpinBox* box = editor.spinBox(field.key);
        ASSERT_NE(box, nullptr) << field.key;
        EXPECT_EQ(box->allowedRange().describe(), field.range.describe()) << field.key;
        EXPECT_TRUE(box->toolTip().contains(QString::fromUtf8(field.label))) << field.key;
        EXPECT_DOUBLE_EQ(box->value(), field.userValue(document.project().wheel)) << field.key;
    }
    EXPECT_EQ(editor.spinBox("grouser_count")->decimals(), 0);  // a whole number
    EXPECT_TRUE(editor.lugSummary()->text().startsWith("Smooth wheel"));
}

// Grousers typed one field at a time: each edit is one undo step; the summary says when the lug
// model acts and at which shearing radius (r_s = r + λ_s h_g, docs/model.md "Lugs"); grousers as
// high as the radius are refused with the reason and never reach the model.
TEST(WheelEditor, GrousersAreTypedUndoneAndCheckedAgainstTheRadius) {
    ProjectDocument document;
    test::resetToDefault(document);
    WheelEditor editor(&document, test::resources());
    editor.show();
    const double r = document.project().wheel.radius_m;
    ASSERT_GT(r, 0.02);
    typeInto(editor.spinBox("grouser_height_m"), "0.01");
    typeInto(editor.spinBox("grouser_count"), "24");
    EXPECT_DOUBLE_EQ(document.project().wheel.grouser_height_m, 0.01);
    EXPECT_DOUBLE_EQ(document.project().wheel.grouser_count, 24.0);
    EXPECT_TRUE(document.project().wheel.lugged());
    EXPECT_TRUE(editor.lugSummary()->text().contains("lug model off"))
        << editor.lugSummary()->text().toStdString();
    typeInto(editor.spinBox("lug_effect_coefficient"), "0.5");
    EXPECT_DOUBLE_EQ(document.project().wheel.lug_effect_coefficient, 0.5);
    // 0.5 × 10 mm = 5 mm beyond the rim.
    const QString rs = QString::number((r + 0.005) * 1e3, 'f', 1);
    EXPECT_TRUE(editor.lugSummary()->text().contains("= " + rs + " mm"))
        << editor.lugSummary()->text().toStdString() << " vs " << rs.toStdString();
    EXPECT_EQ(document.undoStack()->count(), 3);
    EXPECT_EQ(document.undoStack()->text(2).toStdString(), "Set wheel λ_s = 0.5");

    // In range on its own ([0, 0.5] m) but not below the radius: refused with the reason.
    const QString too_high = QString::number(r + 0.01, 'f', 4);
    typeInto(editor.spinBox("grouser_height_m"), too_high);
    EXPECT_DOUBLE_EQ(document.project().wheel.grouser_height_m, 0.01);
    EXPECT_EQ(document.undoStack()->count(), 3);
    EXPECT_DOUBLE_EQ(editor.spinBox("grouser_height_m")->value(), 0.01);
    const auto* label = editor.findChild<QLabel*>("message");
    ASSERT_NE(label, nullptr);
    const QString message = label->text();
    EXPECT_TRUE(message.contains("is not below the radius")) << message.toStdString();

    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(document.project().wheel.lug_effect_coefficient, 0.0);
    EXPECT_DOUBLE_EQ(editor.spinBox("lug_effect_coefficient")->value(), 0.0);
    EXPECT_TRUE(editor.lugSummary()->text().contains("lug model off"));
    document.undoStack()->undo();
    document.undoStack()->undo();
    EXPECT_FALSE(document.project().wheel.lugged());
    EXPECT_TRUE(editor.lugSummary()->text().startsWith("Smooth wheel"));
}

TEST(ConditionsEditor, BadSlipAngleListIsFlaggedNotApplied) {
    ProjectDocument document;
    test::resetToDefault(document);
    ConditionsEditor editor(&document);
    editor.show();
    auto* angles = editor.findChild<QLineEdit*>("conditions.slip_angles_deg");
    ASSERT_NE(angles, nullptr);
    angles->setText("5, ten, 95");
    emit angles->editingFinished();
    EXPECT_EQ(document.project().conditions.slip_angles_deg.size(), 6u);
    EXPECT_TRUE(angles->property("invalidMessage").toString().contains("\"ten\" is not a number"));
    angles->setText("0, 15");
    emit angles->editingFinished();
    EXPECT_EQ(document.project().conditions.slip_angles_deg, (std::vector<double>{0.0, 15.0}));
}

// An edited soil is named "sandy loam (edited)" by the document: the tree shows that name once
// (it used to append a second "(edited)"); a name the user types is said to be edited.
TEST(ProjectTree, AnEditedSoilIsSaidToBeEditedOnce) {
    ProjectDocument document;
    test::resetToDefault(document);
    ProjectTree tree(&document);
    QTreeWidgetItem* soil = tree.topLevelItem(ProjectTree::kSoil);
    ASSERT_NE(soil, nullptr);
    // A preset by its name, not its file id (issue 27); the id is in the tooltip.
    EXPECT_EQ(soil->text(1), "sandy loam");
    EXPECT_TRUE(soil->toolTip(1).contains("sandy-loam")) << soil->toolTip(1).toStdString();
    ASSERT_TRUE(document.setSoilValue("phi_deg", 35.0));
    ASSERT_TRUE(document.project().soil_preset.empty());
    const QString name = QString::fromStdString(document.project().soil.name);
    EXPECT_TRUE(name.endsWith("(edited)")) << name.toStdString();
    EXPECT_EQ(soil->text(1), name);
    EXPECT_EQ(soil->text(1).count("(edited)"), 1);
    ASSERT_TRUE(document.setSoilName("my field"));
    EXPECT_EQ(soil->text(1), "my field (edited)");
    EXPECT_EQ(soil->toolTip(1), soil->text(1));
}

// The tree lists the scenarios edited in the rover panel (kept in its settings) as they appear.
TEST(ProjectTree, ListsEditedScenarios) {
    ProjectDocument document;
    test::resetToDefault(document);
    ProjectTree tree(&document);
    QTreeWidgetItem* scenarios = tree.topLevelItem(ProjectTree::kScenarios);
    ASSERT_NE(scenarios, nullptr);
    EXPECT_EQ(scenarios->childCount(), 0);
    document.setPanelSettings(
        "rover", {{"scenario", "straight"},
                  {"edited",
                   {{"straight", {{"duration_s", 5.0}}}, {"soil-border", {{"duration_s", 9.0}}}}}});
    ASSERT_EQ(scenarios->childCount(), 2);
    EXPECT_EQ(scenarios->text(1), "2");
    EXPECT_EQ(scenarios->child(0)->text(1), "edited");
}

}  // namespace
}  // namespace terra::ui
