#pragma once
/// @file property_editors.h
/// The property editors of the studio's right-hand side: soil (preset + every field of the core's
/// field table with unit, range-validated spin box and slider), wheel (preset, r, b) and operating
/// conditions. They write only through the document's setters (one undo command each) and follow
/// its signals back, with signal blockers against feedback loops.

#include <QWidget>
#include <map>
#include <string>

#include "core/io/parameters_json.h"

class QComboBox;
class QLineEdit;
class QSlider;

namespace terra::ui {

class ProjectDocument;
class ValidatedSpinBox;

class SoilEditor : public QWidget {
    Q_OBJECT
public:
    SoilEditor(ProjectDocument* document, const io::PresetLocations& locations, QWidget* parent = nullptr);
    /// The spin box of a field key ("phi_deg"), for tests and for focusing from the tree.
    ValidatedSpinBox* spinBox(const std::string& key) const;

private:
    void refresh();
    ProjectDocument* document_;
    io::PresetLocations locations_;
    QComboBox* preset_;
    std::map<std::string, std::pair<ValidatedSpinBox*, QSlider*>> fields_;
};

class WheelEditor : public QWidget {
    Q_OBJECT
public:
    WheelEditor(ProjectDocument* document, const io::PresetLocations& locations, QWidget* parent = nullptr);

private:
    void refresh();
    ProjectDocument* document_;
    io::PresetLocations locations_;
    QComboBox* preset_;
    ValidatedSpinBox* radius_;
    ValidatedSpinBox* width_;
};

class ConditionsEditor : public QWidget {
    Q_OBJECT
public:
    explicit ConditionsEditor(ProjectDocument* document, QWidget* parent = nullptr);
    ValidatedSpinBox* loadBox() const { return load_; }

private:
    void refresh();
    ProjectDocument* document_;
    ValidatedSpinBox* load_;
    QLineEdit* slip_angles_;
};

}  // namespace terra::ui
