#pragma once
/// @file property_editors.h
/// The property editors of the studio's right-hand side: soil (preset + every field of the core's
/// field table with unit, range-validated spin box and slider), wheel (preset and every field of
/// the wheel's table: r, b, the grousers and the lug-effect coefficient) and operating conditions.
/// They write only through the document's setters (one undo command each) and follow its signals
/// back, with signal blockers against feedback loops.

#include <QWidget>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/io/parameters_json.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QSlider;

namespace terra::ui {

class ProjectDocument;
class ValidatedSpinBox;

/// The mapping between a field's slider position and its value. Narrow ranges are linear (1000
/// steps); spans ≥ 100 that are also ≥ 10⁴ × the box's resolution (c, k_c, k_φ) use a signed-log
/// mapping u = sign(v) log10(1 + |v| / knee) over 10000 steps, so small values stay reachable and a
/// step near a typical value is fine (k_φ = 1515 kN/m^(n+2): ~1.7 per step instead of 100).
struct SliderScale {
    double minimum = 0.0, maximum = 1.0;
    bool logarithmic = false;
    double knee = 1.0;  ///< where the log mapping turns linear: 10 × the box's resolution
    int steps = 1000;

    static SliderScale forBox(const QDoubleSpinBox& box);
    int toSlider(double value) const;
    double fromSlider(int position) const;

private:
    double warp(double value) const;
    double unwarp(double u) const;
};

class SoilEditor : public QWidget {
    Q_OBJECT
public:
    SoilEditor(ProjectDocument* document, const io::PresetLocations& locations,
               QWidget* parent = nullptr);
    /// Its fields stop talking to the document first: ~QWidget hides them, and a field with
    /// typed text commits it on losing the focus, into an editor half destroyed.
    ~SoilEditor() override;
    /// The spin box of a field key ("phi_deg"), for tests and for focusing from the tree.
    ValidatedSpinBox* spinBox(const std::string& key) const;
    QSlider* slider(const std::string& key) const;

private:
    void refresh();
    ProjectDocument* document_;
    io::PresetLocations locations_;
    QComboBox* preset_;
    QLineEdit* name_;
    QLabel* message_;  // what is wrong with the text being typed
    std::map<std::string, std::pair<ValidatedSpinBox*, QSlider*>> fields_;
};

class WheelEditor : public QWidget {
    Q_OBJECT
public:
    WheelEditor(ProjectDocument* document, const io::PresetLocations& locations,
                QWidget* parent = nullptr);
    /// Its fields stop talking to the document first: ~QWidget hides them, and a field with
    /// typed text commits it on losing the focus, into an editor half destroyed.
    ~WheelEditor() override;
    /// The spin box of a wheel field key ("r_m", "grouser_count", …), for tests.
    ValidatedSpinBox* spinBox(const std::string& key) const;
    /// The line that says whether the lug model acts on this wheel, and how.
    QLabel* lugSummary() const { return lug_summary_; }

private:
    void refresh();
    ProjectDocument* document_;
    io::PresetLocations locations_;
    QComboBox* preset_;
    std::map<std::string, ValidatedSpinBox*> fields_;
    QLabel* lug_summary_;
    QLabel* message_;
};

class ConditionsEditor : public QWidget {
    Q_OBJECT
public:
    explicit ConditionsEditor(ProjectDocument* document, QWidget* parent = nullptr);
    /// Its fields stop talking to the document first: ~QWidget hides them, and a field with
    /// typed text commits it on losing the focus, into an editor half destroyed.
    ~ConditionsEditor() override;
    ValidatedSpinBox* loadBox() const { return load_; }
    QLineEdit* slipAnglesEdit() const { return slip_angles_; }

private:
    void refresh();
    /// The typed list, or nothing: then the field is tinted and the message names the first bad
    /// entry and the allowed range.
    std::optional<std::vector<double>> checkSlipAngles();
    ProjectDocument* document_;
    ValidatedSpinBox* load_;
    QLineEdit* slip_angles_;
    QLabel* message_;
};

}  // namespace terra::ui
