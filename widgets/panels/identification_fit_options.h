#pragma once
/// @file identification_fit_options.h
/// The batch fit's options on the identification panel's fit page (identification_fit_page.h):
/// the method (full model with its global search, or the thesis's decoupled fit), the held-out
/// validation, the loss, the prior (a soil preset and items), the wheel the model is fitted with
/// (the data's when a sidecar JSON beside the CSV names one, else the project's, or a preset) and
/// j_max; and the sentences that say what the fit starts from and which wheel it uses. The page
/// lays out its three rows.

#include <QObject>
#include <QString>
#include <optional>
#include <vector>

#include "core/common/issue.h"
#include "core/project/panels.h"
#include "core/wheel/wheel_parameters.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QHBoxLayout;
class QLabel;
class QLineEdit;
class QWidget;

namespace terra::ui {

class ProjectDocument;

class IdentificationFitOptions : public QObject {
    Q_OBJECT
public:
    /// Creates the option controls on `page`; `full_model` is the method's check box (the page's
    /// first row holds it).
    IdentificationFitOptions(ProjectDocument* document, QCheckBox* full_model, QWidget* page);

    /// The rows for the page's layout: method, validation and loss; wheel and j_max with the
    /// sentence on the wheel; the prior.
    QHBoxLayout* methodRow() const { return method_row_; }
    QHBoxLayout* modelRow() const { return model_row_; }
    QHBoxLayout* priorRow() const { return prior_row_; }
    /// The sentence on what the fit starts from.
    QLabel* startLabel() const { return start_; }

    bool fullModel() const;
    /// The data file the fit reads ("" for synthetic data): the data's wheel and the sentences
    /// follow it.
    void setDataFile(const QString& csv);
    /// The options' part of the panel's saved settings, and setting them from it.
    void writeSettings(project::IdentificationPanelSettings& s) const;
    void applySettings(const project::IdentificationPanelSettings& s);
    /// j_max's mode for the fit: the control's with the full model, else "auto".
    QString jmaxMode() const;
    /// What is wrong with the prior items, each named (empty: none, or the decoupled fit).
    std::vector<Issue> priorIssues() const;

    QString startDescription() const;
    void setFitOptions(const QString& prior_soil, const QString& prior_items,
                       const QString& validation, const QString& loss);
    void setWheelChoice(const QString& choice);
    wheel::WheelParameters chosenWheel() const;
    QString wheelDescription() const;
    const std::optional<wheel::WheelParameters>& dataWheel() const { return data_wheel_; }
    void setShearLimit(const QString& mode, double jmax_mm);

private:
    void updateControls();
    void updateWheelChoices();

    ProjectDocument* document_;
    QCheckBox* refine_;
    QComboBox* prior_soil_;
    QLineEdit* prior_items_;
    QComboBox* validation_;
    QComboBox* loss_;
    QLabel* start_;
    QComboBox* wheel_;
    QLabel* wheel_note_;
    QComboBox* jmax_mode_;
    QDoubleSpinBox* jmax_value_;
    QHBoxLayout* method_row_;
    QHBoxLayout* model_row_;
    QHBoxLayout* prior_row_;
    QString csv_;                                       // the data file, trimmed
    std::optional<wheel::WheelParameters> data_wheel_;  // named by the CSV's sidecar
    QString data_wheel_source_;                         // that sidecar's file name
};

}  // namespace terra::ui
