#include "widgets/editors/property_editors.h"

#include <QComboBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <limits>

#include "widgets/document/project_document.h"
#include "widgets/editors/validated_spin_box.h"

namespace terra::ui {
namespace {

int decimalsFor(const Range& range) {
    const double span = range.high - range.low;
    if (span >= 1000.0) return 1;
    if (span >= 10.0) return 2;
    return 4;
}

}  // namespace

SliderScale SliderScale::forBox(const QDoubleSpinBox& box) {
    SliderScale scale;
    scale.minimum = box.minimum();
    scale.maximum = box.maximum();
    const double resolution = std::pow(10.0, -box.decimals());
    // Wide ranges (c, k_c, k_φ: spans of hundreds or more and 4–6 decades above the box's
    // resolution) get the signed-log mapping; a linear slider of 1000 steps would move k_φ by
    // 100 kN/m^(n+2) a step. Narrow ones (n, φ, a₀, a₁, K, γ, j_max) stay linear.
    const double span = scale.maximum - scale.minimum;
    scale.logarithmic = span >= 100.0 && span / resolution >= 1e4;
    scale.steps = scale.logarithmic ? 10000 : 1000;
    scale.knee = 10.0 * resolution;
    return scale;
}

double SliderScale::warp(double value) const {
    if (!logarithmic) return value;
    return std::copysign(std::log10(1.0 + std::abs(value) / knee), value);
}

double SliderScale::unwarp(double u) const {
    if (!logarithmic) return u;
    return std::copysign(knee * (std::pow(10.0, std::abs(u)) - 1.0), u);
}

int SliderScale::toSlider(double value) const {
    const double lo = warp(minimum), hi = warp(maximum);
    const double t = (warp(std::clamp(value, minimum, maximum)) - lo) / (hi - lo);
    return static_cast<int>(std::lround(std::clamp(t, 0.0, 1.0) * steps));
}

double SliderScale::fromSlider(int position) const {
    if (position <= 0) return minimum;  // exact ends: no rounding drift through log/pow
    if (position >= steps) return maximum;
    const double lo = warp(minimum), hi = warp(maximum);
    return std::clamp(unwarp(lo + (hi - lo) * position / steps), minimum, maximum);
}

namespace {

QComboBox* presetBox(const io::PresetLocations& locations, const char* kind, QWidget* parent) {
    auto* box = new QComboBox(parent);
    box->addItem("(custom)", QString());
    for (const std::string& name : io::presetNames(locations, kind)) {
        box->addItem(QString::fromStdString(name), QString::fromStdString(name));
    }
    return box;
}

void selectPreset(QComboBox* box, const std::string& preset) {
    const QSignalBlocker block(box);
    const int i = box->findData(QString::fromStdString(preset));
    box->setCurrentIndex(i >= 0 ? i : 0);
}

}  // namespace

SoilEditor::SoilEditor(ProjectDocument* document, const io::PresetLocations& locations,
                       QWidget* parent)
    : QWidget(parent), document_(document), locations_(locations) {
    preset_ = presetBox(locations_, "soils", this);
    auto* grid = new QGridLayout;
    grid->addWidget(new QLabel("<b>Soil preset</b>", this), 0, 0);
    grid->addWidget(preset_, 0, 1, 1, 2);
    int row = 1;
    for (const soil::SoilField& field : soil::soilFields()) {
        const bool jmax = std::string(field.key) == "jmax_m";
        auto* box = new ValidatedSpinBox(field, decimalsFor(field.range), this);
        box->setObjectName(QString("soil.") + field.key);
        if (jmax) {
            // j_max is optional: the lowest value means "no limit" (the field itself excludes 0).
            box->setMinimum(0.0);
            box->setSpecialValueText("no limit");
        }
        auto* slider = new QSlider(Qt::Horizontal, this);
        slider->setObjectName(QString("soil.") + field.key + ".slider");
        slider->setRange(0, SliderScale::forBox(*box).steps);
        slider->setMinimumWidth(90);
        auto* label = new QLabel(
            QString("%1 [%2]").arg(QString::fromUtf8(field.symbol), QString::fromUtf8(field.unit)),
            this);
        label->setToolTip(QString("%1 (%2): %3")
                              .arg(QString::fromUtf8(field.label), QString::fromUtf8(field.key),
                                   QString::fromUtf8(field.description)));
        grid->addWidget(label, row, 0);
        grid->addWidget(box, row, 1);
        grid->addWidget(slider, row, 2);
        ++row;
        const std::string key = field.key;
        fields_[key] = {box, slider};
        connect(box, &QDoubleSpinBox::valueChanged, this, [this, key, box, jmax](double value) {
            const double user =
                jmax && value == 0.0 ? std::numeric_limits<double>::infinity() : value;
            if (jmax && std::isinf(user)) {
                soil::SoilParameters soil = document_->project().soil;
                soil.max_shear_deformation_m = user;
                document_->setSoil(soil, "");
            } else if (!document_->setSoilValue(key, user)) {
                refresh();  // refused by the model (e.g. K_s ≤ 0): show the model's value again
            }
            (void)box;
        });
        connect(slider, &QSlider::valueChanged, this, [box](int position) {
            box->setValue(SliderScale::forBox(*box).fromSlider(position));
        });
    }
    grid->setColumnStretch(2, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(grid);
    layout->addStretch(1);

    connect(preset_, &QComboBox::currentIndexChanged, this, [this] {
        const std::string name = preset_->currentData().toString().toStdString();
        if (name.empty()) return;
        if (auto soil = io::resolveSoil(locations_, name)) document_->setSoil(*soil, name);
    });
    connect(document_, &ProjectDocument::soilChanged, this, &SoilEditor::refresh);
    refresh();
}

ValidatedSpinBox* SoilEditor::spinBox(const std::string& key) const {
    const auto it = fields_.find(key);
    return it == fields_.end() ? nullptr : it->second.first;
}

QSlider* SoilEditor::slider(const std::string& key) const {
    const auto it = fields_.find(key);
    return it == fields_.end() ? nullptr : it->second.second;
}

void SoilEditor::refresh() {
    const Project& project = document_->project();
    selectPreset(preset_, project.soil_preset);
    for (const soil::SoilField& field : soil::soilFields()) {
        auto [box, slider] = fields_.at(field.key);
        const double value = soil::userValue(project.soil, field);
        const QSignalBlocker block_slider(slider);
        box->setCommittedValue(std::isinf(value) ? 0.0 : value);
        slider->setValue(SliderScale::forBox(*box).toSlider(box->value()));
    }
}

WheelEditor::WheelEditor(ProjectDocument* document, const io::PresetLocations& locations,
                         QWidget* parent)
    : QWidget(parent), document_(document), locations_(locations) {
    preset_ = presetBox(locations_, "wheels", this);
    const wheel::WheelField& r = wheel::radiusField();
    const wheel::WheelField& b = wheel::widthField();
    radius_ = new ValidatedSpinBox(r, 4, this);
    radius_->setObjectName(QString("wheel.") + r.key);
    radius_->setSingleStep(0.005);
    width_ = new ValidatedSpinBox(b, 4, this);
    width_->setObjectName(QString("wheel.") + b.key);
    width_->setSingleStep(0.005);
    auto* form = new QFormLayout(this);
    form->addRow("<b>Wheel preset</b>", preset_);
    auto label = [](const FieldInfo& f) {
        const QString text = QString::fromUtf8(f.label);
        return text.left(1).toUpper() + text.mid(1) + " " +
               QString::fromStdString(f.symbolWithUnit());
    };
    form->addRow(label(r), radius_);
    form->addRow(label(b), width_);
    connect(preset_, &QComboBox::currentIndexChanged, this, [this] {
        const std::string name = preset_->currentData().toString().toStdString();
        if (name.empty()) return;
        if (auto wheel = io::resolveWheel(locations_, name)) document_->setWheel(*wheel, name);
    });
    connect(radius_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!document_->setWheelValue(wheel::radiusField().key, v)) refresh();
    });
    connect(width_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!document_->setWheelValue(wheel::widthField().key, v)) refresh();
    });
    connect(document_, &ProjectDocument::wheelChanged, this, &WheelEditor::refresh);
    refresh();
}

void WheelEditor::refresh() {
    const Project& project = document_->project();
    selectPreset(preset_, project.wheel_preset);
    radius_->setCommittedValue(project.wheel.radius_m);
    width_->setCommittedValue(project.wheel.width_m);
}

ConditionsEditor::ConditionsEditor(ProjectDocument* document, QWidget* parent)
    : QWidget(parent), document_(document) {
    const FieldInfo& load = contact::loadField();
    const FieldInfo& angles = analysis::slipAnglesField();
    load_ = new ValidatedSpinBox(load, 2, this);
    load_->setObjectName(QString("conditions.") + load.key);
    load_->setSingleStep(1.0);
    slip_angles_ = new QLineEdit(this);
    slip_angles_->setObjectName(QString("conditions.") + angles.key);
    slip_angles_->setToolTip(QString("%1, comma separated, each in %2")
                                 .arg(QString::fromUtf8(angles.description),
                                      QString::fromStdString(angles.range.describe())));
    auto* form = new QFormLayout(this);
    form->addRow(QString("Load %1").arg(QString::fromStdString(load.symbolWithUnit())), load_);
    form->addRow(QString("Slip angles %1").arg(QString::fromStdString(angles.symbolWithUnit())),
                 slip_angles_);
    connect(load_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!document_->setLoad(v)) refresh();
    });
    connect(slip_angles_, &QLineEdit::editingFinished, this, [this] {
        std::vector<double> values;
        bool ok = true;
        for (const QString& part : slip_angles_->text().split(',', Qt::SkipEmptyParts)) {
            bool parsed = false;
            const double v = part.trimmed().toDouble(&parsed);
            ok = ok && parsed && analysis::slipAnglesField().range.contains(v);
            values.push_back(v);
        }
        if (!ok || values.empty() || !document_->setSlipAngles(values)) {
            slip_angles_->setStyleSheet("QLineEdit { border: 2px solid #d62728; }");
            slip_angles_->setToolTip(
                QString("Not a comma-separated list of angles in %1 deg: not applied")
                    .arg(QString::fromStdString(analysis::slipAnglesField().range.describe())));
            return;
        }
        slip_angles_->setStyleSheet({});
    });
    connect(document_, &ProjectDocument::conditionsChanged, this, &ConditionsEditor::refresh);
    refresh();
}

void ConditionsEditor::refresh() {
    const analysis::OperatingConditions& c = document_->project().conditions;
    load_->setCommittedValue(c.load_n);
    QStringList angles;
    for (double beta : c.slip_angles_deg) angles << QString::number(beta);
    slip_angles_->setText(angles.join(", "));
    slip_angles_->setStyleSheet({});
}

}  // namespace terra::ui
