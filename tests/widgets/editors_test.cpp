// The property editors: invalid text is flagged at the field and never reaches the model; valid
// edits go through the document (undoable).
#include <gtest/gtest.h>

#include <QComboBox>
#include <QLineEdit>
#include <QTest>
#include <QUndoStack>
#include <cmath>

#include "core/common/units.h"
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
        [&] { return std::abs(document.project().soil.friction_angle_rad - units::degToRad(33.0)) < 1e-12; },
        10 * phi->debounceMs()));
    EXPECT_EQ(document.undoStack()->count(), 1);  // one undo command for the settled edit
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, before);
    EXPECT_DOUBLE_EQ(phi->value(), 29.0);

    // Two settled edits of one field merge into one undo step (the document's merge id).
    phi->selectAll();
    QTest::keyClicks(phi, "31");
    ASSERT_TRUE(QTest::qWaitFor([&] { return document.project().soil.friction_angle_rad != before; }, 3000));
    phi->selectAll();
    QTest::keyClicks(phi, "32");
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return std::abs(document.project().soil.friction_angle_rad - units::degToRad(32.0)) < 1e-12; },
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
    QTest::keyClicks(load, "6000");  // W ≤ 5000 N (a typed "-" is refused outright: W > 0)
    QTest::qWait(3 * load->debounceMs());
    EXPECT_DOUBLE_EQ(document.project().conditions.load_n, 58.86);
    EXPECT_EQ(document.undoStack()->count(), 0);
}

TEST(SoilEditor, EveryFieldOfTheCoreTableHasAnEditorWithItsRange) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    for (const soil::SoilField& field : soil::soilFields()) {
        ValidatedSpinBox* box = editor.spinBox(field.key);
        ASSERT_NE(box, nullptr) << field.key;
        EXPECT_EQ(box->allowedRange().describe(), field.range.describe()) << field.key;
        EXPECT_TRUE(box->toolTip().contains(QString::fromUtf8(field.unit))) << field.key;
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
    EXPECT_TRUE(angles->styleSheet().contains("border"));
    angles->setText("0, 15");
    emit angles->editingFinished();
    EXPECT_EQ(document.project().conditions.slip_angles_deg, (std::vector<double>{0.0, 15.0}));
}

}  // namespace
}  // namespace terra::ui
