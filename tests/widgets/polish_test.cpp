// Issue 27, item 6 (polish): numbers with the digits their std or size supports, an editor's
// message that goes stale goes away, a refused keystroke named as a key in a named field, small
// values shown in the fields, and presets by their names.
#include <gtest/gtest.h>

#include <QAction>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QPushButton>
#include <QTest>

#include "widgets/editors/property_editors.h"
#include "widgets/editors/validated_spin_box.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/plots/experiment_overlay.h"
#include "widgets/plots/number_format.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

QString messageOf(const QWidget& editor) { return editor.findChild<QLabel*>("message")->text(); }

/// Digits after the decimal point of a number's text ("0.0137" → 4, "73" → 0).
int decimalsOf(const QString& text) {
    const qsizetype point = text.indexOf('.');
    return point < 0 ? 0 : static_cast<int>(text.size() - point - 1);
}

TEST(PanelNumberFormat, ValuesCarryTheDigitsTheirStdSupports) {
    EXPECT_EQ(formatStd(0.0137), "0.014");
    EXPECT_EQ(formatStd(73.2), "73");
    EXPECT_EQ(formatStd(0.84), "0.84");
    EXPECT_EQ(formatStd(0.0), "–");
    EXPECT_EQ(formatWithStd(28.829, 0.84), "28.83");
    EXPECT_EQ(formatWithStd(1610.8, 73), "1611");
    EXPECT_EQ(formatWithStd(0.18594, 0.0137), "0.186");
    // c = 0.0023 kPa is not "0.00", and a value that rounds to zero at its std is "0", not "-0".
    EXPECT_EQ(formatWithStd(0.0023, 0.0011), "0.0023");
    EXPECT_EQ(formatWithStd(-0.0004, 0.19), "0");
}

TEST(PanelNumberFormat, RoundingNoiseIsZeroAndSmallValuesKeepTheirDigits) {
    EXPECT_EQ(formatNumber(-1.25e-18, 100.0), "0");  // c at its bound of 0 kPa
    EXPECT_EQ(formatNumber(0.0023, 100.0), "0.0023");
    EXPECT_EQ(formatNumber(28.8297394, 60.0), "28.83");
    EXPECT_EQ(formatNumber(1515000.0, 0.0), "1.515e+06");
    EXPECT_EQ(formatNumber(0.5, 1.0), "0.5");
    // An error of 4.945e-15 mm beside one of 2.3 mm is 0 mm; alone it is what it is.
    EXPECT_EQ(channelValue(io::kExpSinkage, 4.945e-18, 2.3e-3), "0 mm");
    EXPECT_EQ(channelValue(io::kExpSinkage, 2.3e-3, 2.3e-3), "2.3 mm");
    EXPECT_EQ(channelValue(io::kExpFx, 5.6561, 0.0), "5.656 N");
}

// The fitted parameters' table: each value to the decimal place of its std.
TEST(PanelNumberFormat, TheIdentifiedParametersShowTheDigitsOfTheirStd) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    int checked = 0;
    for (int row = 0; row < 8; ++row) {
        const QString value = panel.parameterCell(row, 1), std = panel.parameterCell(row, 2);
        EXPECT_FALSE(value.contains('e')) << value.toStdString();
        if (std == "–") continue;
        EXPECT_EQ(decimalsOf(value), decimalsOf(std))
            << panel.parameterCell(row, 0).toStdString() << ": " << value.toStdString() << " ± "
            << std.toStdString();
        ++checked;
    }
    EXPECT_GE(checked, 6);
}

TEST(EditorSpinBox, ASmallValueFromTheModelIsShownNotRoundedAway) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    ASSERT_TRUE(document.setSoilValue("c_kPa", 0.0023));
    EXPECT_EQ(editor.spinBox("c_kPa")->cleanText(), "0.0023");  // it read "0.00"
    ASSERT_TRUE(document.setSoilValue("c_kPa", 1.7));
    EXPECT_EQ(editor.spinBox("c_kPa")->cleanText(), "1.70");  // the box's own decimals again
}

// A calibrated k_φ of 2936.28451 showed all five decimals: at most six significant digits, and
// the document keeps its value (only the text is shorter).
TEST(EditorSpinBox, AFittedValueShowsNoMoreThanSixSignificantDigits) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    ASSERT_TRUE(document.setSoilValue("kphi", 2936.28451));
    EXPECT_EQ(editor.spinBox("kphi")->cleanText(), "2936.3");
    EXPECT_DOUBLE_EQ(document.project().soil.frictional_modulus, 2936.28451e3);
    emit editor.spinBox("kphi")->editingFinished();  // left without typing: nothing pushed
    EXPECT_DOUBLE_EQ(document.project().soil.frictional_modulus, 2936.28451e3);
    EXPECT_EQ(document.undoStack()->count(), 1);
    ASSERT_TRUE(document.setSoilValue("kphi", 1515.04));  // exact in six digits: shown so
    EXPECT_EQ(editor.spinBox("kphi")->cleanText(), "1515.04");
    ASSERT_TRUE(document.setSoilValue("n", 0.8747123));  // the box's four decimals
    EXPECT_EQ(editor.spinBox("n")->cleanText(), "0.8747");
    ASSERT_TRUE(document.setSoilValue("c_kPa", 0.00234));  // small: still shown, not "0.00"
    EXPECT_EQ(editor.spinBox("c_kPa")->cleanText(), "0.00234");
}

// "c: "c" is not a number" read as if the field were the problem.
TEST(EditorSpinBox, ARefusedKeystrokeIsNamedAsAKeyOfANamedField) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    ValidatedSpinBox* c = editor.spinBox("c_kPa");
    c->setFocus();
    c->selectAll();
    QTest::keyClicks(c, "c");
    const QString message = messageOf(editor);
    EXPECT_TRUE(message.startsWith("Cohesion c [kPa] takes a number")) << message.toStdString();
    EXPECT_TRUE(message.contains("the key \"c\"")) << message.toStdString();
    EXPECT_DOUBLE_EQ(c->value(), 1.7);
    // Appended to a number: the key, not the whole text.
    c->selectAll();
    QTest::keyClicks(c, "1.5x");
    EXPECT_TRUE(messageOf(editor).contains("the key \"x\"")) << messageOf(editor).toStdString();
}

// A value in range with more decimals than the box showed was refused as "outside the allowed
// range [0, 200]" (a new user's audit, issue 27): the box takes it, as it shows a file's 0.00234,
// up to its most decimals; beyond those it says so, not "out of range".
TEST(EditorRefusalMessages, MoreDecimalsAreTakenAndNeverCalledOutOfRange) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    ValidatedSpinBox* c = editor.spinBox("c_kPa");
    ASSERT_EQ(c->decimals(), 2);
    c->setFocus();
    c->selectAll();
    QTest::keyClicks(c, "0.0023");
    EXPECT_TRUE(
        QTest::qWaitFor([&document] { return document.project().soil.cohesion_pa == 2.3; }, 3000))
        << document.project().soil.cohesion_pa;
    EXPECT_EQ(c->cleanText(), "0.0023");
    EXPECT_TRUE(messageOf(editor).isEmpty()) << messageOf(editor).toStdString();
    // Beyond the box's most decimals (6): said as such, not committed.
    c->selectAll();
    QTest::keyClicks(c, "0.00000001");
    QTest::qWait(50);  // the box took what it could (6 decimals) after the keys
    const QString message = messageOf(editor);
    EXPECT_TRUE(message.contains("keeps 6 decimals")) << message.toStdString();
    EXPECT_FALSE(message.contains("outside")) << message.toStdString();
    QTest::qWait(600);
    EXPECT_DOUBLE_EQ(document.project().soil.cohesion_pa, 2.3);
    // An exact value typed with extra zeros ("1.500" in a box of two decimals), and Enter at
    // once after the keys (before the raise was queued to run): taken, not refused or reverted.
    c->selectAll();
    QTest::keyClicks(c, "1.500");
    QTest::keyClick(c, Qt::Key_Return);
    EXPECT_TRUE(QTest::qWaitFor(
        [&document] { return document.project().soil.cohesion_pa == 1500.0; }, 3000))
        << document.project().soil.cohesion_pa;
    EXPECT_TRUE(messageOf(editor).isEmpty()) << messageOf(editor).toStdString();
    c->selectAll();
    QTest::keyClicks(c, "0.0005");
    QTest::keyClick(c, Qt::Key_Return);
    EXPECT_TRUE(
        QTest::qWaitFor([&document] { return document.project().soil.cohesion_pa == 0.5; }, 3000))
        << document.project().soil.cohesion_pa;
    // Out of range is still said so.
    c->selectAll();
    QTest::keyClicks(c, "250");
    EXPECT_TRUE(messageOf(editor).contains("outside the allowed range"))
        << messageOf(editor).toStdString();
}

// A refused grouser height stayed under the wheel's fields many edits later.
TEST(EditorStaleMessages, AnEditorsRefusalGoesAtTheNextEditOfTheProject) {
    ProjectDocument document;
    test::resetToDefault(document);
    WheelEditor editor(&document, test::resources());
    ValidatedSpinBox* height = editor.spinBox("grouser_height_m");
    ASSERT_NE(height, nullptr);
    height->setValue(0.1);  // as high as the 0.092 m radius: refused
    ASSERT_TRUE(messageOf(editor).contains("grouser_height_m")) << messageOf(editor).toStdString();
    ASSERT_TRUE(document.setSoilValue("phi_deg", 30.0));  // some edit, elsewhere
    EXPECT_TRUE(messageOf(editor).isEmpty()) << messageOf(editor).toStdString();

    // A field still showing bad text keeps its message through other edits.
    editor.show();
    ValidatedSpinBox* radius = editor.spinBox("r_m");
    radius->setFocus();
    radius->selectAll();
    QTest::keyClicks(radius, "75");
    ASSERT_FALSE(radius->textIsValid());
    const QString flagged = messageOf(editor);
    ASSERT_FALSE(flagged.isEmpty());
    ASSERT_TRUE(document.setSoilValue("phi_deg", 31.0));
    EXPECT_EQ(messageOf(editor), flagged);
}

TEST(EditorPresetNames, PresetsAreListedByNameAndStoredById) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    auto* preset = editor.findChild<QComboBox*>();
    ASSERT_NE(preset, nullptr);
    EXPECT_EQ(preset->currentText(), "sandy loam");
    EXPECT_EQ(preset->currentData().toString(), "sandy-loam");
    EXPECT_GE(preset->findText("clayey soil"), 0);
    EXPECT_LT(preset->findText("clayey-soil"), 0);

    // The identification's prior: by name on screen, by id in the settings.
    IdentificationPanel panel(&document);
    panel.setFitOptions("clayey-soil", "", "none", "l2");
    EXPECT_TRUE(panel.startDescription().contains("clayey soil preset"))
        << panel.startDescription().toStdString();
    EXPECT_EQ(panel.settings()["prior_soil"], "clayey-soil");
    EXPECT_EQ(panel.settings()["stream_second_soil"], "clayey-soil");

    // "Compare with…" lists the presets by name.
    ForcesPanel forces(&document);
    forces.setPresetLocations(test::resources());
    forces.compareButton()->menu()->aboutToShow();  // the menu lists the presets when it opens
    auto* action =
        forces.compareButton()->menu()->findChild<QAction*>("forces.compare_preset.clayey-soil");
    ASSERT_NE(action, nullptr);
    EXPECT_EQ(action->text(), "clayey soil");
}

}  // namespace
}  // namespace terra::ui
