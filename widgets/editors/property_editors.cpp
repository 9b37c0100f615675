#include "widgets/editors/property_editors.h"

#include <QComboBox>
#include <QEvent>
#include <QFormLayout>
#include <QGridLayout>
#include <QKeyEvent>
#include <QKeySequence>
#include <QLabel>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "widgets/document/project_document.h"
#include "widgets/editors/preset_names.h"
#include "widgets/editors/validated_spin_box.h"

namespace terra::ui {
namespace {

void silenceFields(QWidget* editor) {
    for (QWidget* field : editor->findChildren<QWidget*>()) field->blockSignals(true);
}

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
    addPresetItems(box, locations, kind);  // "sandy loam", not "sandy-loam"
    return box;
}

/// An editor's message line describes its last refused edit: any later edit of the project
/// makes it stale (a grouser error stayed many edits later), unless a field still shows bad text.
void clearStaleMessage(QLabel* message, const QWidget* editor) {
    for (const QWidget* field : editor->findChildren<QWidget*>()) {
        if (!field->property("invalidMessage").toString().isEmpty()) return;
    }
    message->clear();
}

/// Selects the preset, or the first item named after the custom soil or wheel ("sandy loam
/// (edited)") when there is none.
void selectPreset(QComboBox* box, const std::string& preset, const std::string& custom_name) {
    const QSignalBlocker block(box);
    box->setItemText(
        0, custom_name.empty() ? QString("(custom)") : QString::fromStdString(custom_name));
    const int i = preset.empty() ? 0 : box->findData(QString::fromStdString(preset));
    box->setCurrentIndex(i >= 0 ? i : 0);
}

/// The line under an editor's fields that says what is wrong with the text being typed. It keeps
/// its two lines of height when empty, so a message never moves the fields.
QLabel* messageLabel(QWidget* parent) {
    auto* label = new QLabel(parent);
    label->setObjectName("message");
    label->setWordWrap(true);
    label->setMinimumHeight(2 * label->fontMetrics().lineSpacing() + 4);
    label->setAlignment(Qt::AlignLeft | Qt::AlignTop);
    QPalette palette = label->palette();
    palette.setColor(QPalette::WindowText, QColor(192, 57, 43));
    label->setPalette(palette);
    return label;
}

/// Lets Ctrl+Z / Ctrl+Y reach the studio's undo stack from a line edit whose text is unchanged
/// (a QLineEdit claims them for its own text undo otherwise).
class UndoPassThrough : public QObject {
public:
    using QObject::QObject;
    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() == QEvent::ShortcutOverride) {
            auto* key = static_cast<QKeyEvent*>(event);
            auto* edit = qobject_cast<QLineEdit*>(watched);
            const bool shortcut =
                key->matches(QKeySequence::Undo) || key->matches(QKeySequence::Redo) ||
                QKeySequence(key->keyCombination()) == QKeySequence(Qt::CTRL | Qt::Key_Y);
            if (shortcut && edit && !edit->isModified()) {
                event->ignore();
                return true;
            }
        }
        return QObject::eventFilter(watched, event);
    }
};

void passUndoShortcuts(QLineEdit* edit) { edit->installEventFilter(new UndoPassThrough(edit)); }

}  // namespace

SoilEditor::SoilEditor(ProjectDocument* document, const io::PresetLocations& locations,
                       QWidget* parent)
    : QWidget(parent), document_(document), locations_(locations) {
    preset_ = presetBox(locations_, "soils", this);
    preset_->setToolTip(
        "A soil of resources/soils (docs/soils.md). Editing a field leaves the "
        "preset: the soil is then named \"<preset> (edited)\" or as you name it.");
    name_ = new QLineEdit(this);
    name_->setObjectName("soil.name");
    name_->setToolTip("The soil's name: plot titles, exports and the .terra file carry it.");
    passUndoShortcuts(name_);
    message_ = messageLabel(this);
    auto* grid = new QGridLayout;
    // The preset box on its own row, the pane's whole width: beside the labels' column it made the
    // pane wider than the compact layout's 280 px (a sideways scroll bar at 1024×700).
    grid->addWidget(new QLabel("<b>Soil preset</b>", this), 0, 0, 1, 3);
    grid->addWidget(preset_, 1, 0, 1, 3);
    grid->addWidget(new QLabel("Name", this), 2, 0);
    grid->addWidget(name_, 2, 1, 1, 2);
    int row = 3;
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
        slider->setMinimumWidth(40);  // enough to drag; the compact pane is 280 px
        auto* label = new QLabel(
            QString("%1 [%2]").arg(QString::fromUtf8(field.symbol), QString::fromUtf8(field.unit)),
            this);
        label->setToolTip(box->toolTip());
        slider->setToolTip(box->toolTip());
        grid->addWidget(label, row, 0);
        grid->addWidget(box, row, 1);
        grid->addWidget(slider, row, 2);
        ++row;
        const std::string key = field.key;
        fields_[key] = {box, slider};
        connect(box, &QDoubleSpinBox::valueChanged, this, [this, key, jmax](double value) {
            // The lowest value of j_max's box is "no limit" (+inf for the model).
            const double user =
                jmax && value == 0.0 ? std::numeric_limits<double>::infinity() : value;
            if (!document_->setSoilValue(key, user)) {
                refresh();  // refused by the model (e.g. K_s ≤ 0): show the model's value again
            }
        });
        // A drag is one undo step, a value typed afterwards another (and the other way round).
        connect(slider, &QSlider::sliderReleased, document_, &ProjectDocument::endMerge);
        connect(box, &ValidatedSpinBox::editingStarted, document_, &ProjectDocument::endMerge);
        connect(box, &QDoubleSpinBox::editingFinished, document_, &ProjectDocument::endMerge);
        connect(box, &ValidatedSpinBox::messageChanged, message_, &QLabel::setText);
        connect(slider, &QSlider::valueChanged, this, [box](int position) {
            box->setValue(SliderScale::forBox(*box).fromSlider(position));
        });
    }
    grid->setColumnStretch(2, 1);
    // Rows 3 px apart (the style's 6 made the pane 19 px too tall for the compact layout at
    // 1024×700: a vertical scroll bar over the most edited page).
    grid->setVerticalSpacing(3);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addLayout(grid);
    layout->addWidget(message_);
    layout->addStretch(1);
    connect(name_, &QLineEdit::editingFinished, this, [this] {
        const std::string name = name_->text().trimmed().toStdString();
        if (name.empty() || !document_->setSoilName(name)) refresh();
    });

    connect(preset_, &QComboBox::currentIndexChanged, this, [this] {
        const std::string name = preset_->currentData().toString().toStdString();
        if (name.empty()) return;
        if (auto soil = io::resolveSoil(locations_, name)) document_->setSoil(*soil, name);
    });
    connect(document_, &ProjectDocument::soilChanged, this, &SoilEditor::refresh);
    connect(document_, &ProjectDocument::changed, message_,
            [this] { clearStaleMessage(message_, this); });
    refresh();
}

SoilEditor::~SoilEditor() { silenceFields(this); }

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
    selectPreset(preset_, project.soil_preset,
                 project.soil_preset.empty() ? project.soil.name : "");
    if (!name_->hasFocus() || !name_->isModified())
        name_->setText(QString::fromStdString(project.soil.name));
    for (const soil::SoilField& field : soil::soilFields()) {
        auto [box, slider] = fields_.at(field.key);
        const double value = soil::userValue(project.soil, field);
        const QSignalBlocker block_slider(slider);
        box->setCommittedValue(std::isinf(value) ? 0.0 : value);
        slider->setValue(SliderScale::forBox(*box).toSlider(box->value()));
    }
}

namespace {

/// Decimals and step of a wheel field's box: r and b to 0.1 mm, the grousers to 0.1 mm, the count
/// whole, λ_s to 0.01.
std::pair<int, double> wheelBoxResolution(const wheel::WheelField& field) {
    const std::string key = field.key;
    if (key == "grouser_count") return {0, 1.0};
    if (key == "lug_effect_coefficient") return {2, 0.05};
    if (key == "grouser_height_m" || key == "grouser_thickness_m") return {4, 0.001};
    return {4, 0.005};
}

/// What the lug model does with this wheel, in one line (docs/model.md, "Lugs").
QString lugSummaryText(const wheel::WheelParameters& w) {
    if (!w.lugged()) return "Smooth wheel: the thesis model.";
    if (w.lug_effect_coefficient <= 0.0)
        return QString("%1 grousers of %2 mm; lug model off (λ_s = 0): sheared as a smooth wheel.")
            .arg(w.grouser_count)
            .arg(w.grouser_height_m * 1e3, 0, 'g', 4);
    return QString("Lug model on: the soil shears at r_s = r + λ_s h_g = %1 mm (r = %2 mm).")
        .arg((w.radius_m + w.lugShearOffset()) * 1e3, 0, 'f', 1)
        .arg(w.radius_m * 1e3, 0, 'f', 1);
}

}  // namespace

WheelEditor::WheelEditor(ProjectDocument* document, const io::PresetLocations& locations,
                         QWidget* parent)
    : QWidget(parent), document_(document), locations_(locations) {
    preset_ = presetBox(locations_, "wheels", this);
    message_ = messageLabel(this);
    lug_summary_ = new QLabel(this);
    lug_summary_->setObjectName("wheel.lug_summary");
    lug_summary_->setWordWrap(true);
    auto* form = new QFormLayout(this);
    // A label too long for the pane's width goes above its field, not past the pane's edge.
    form->setRowWrapPolicy(QFormLayout::WrapLongRows);
    form->addRow("<b>Wheel preset</b>", preset_);
    auto label = [](const FieldInfo& f) {
        const QString text = QString::fromUtf8(f.label);
        return text.left(1).toUpper() + text.mid(1) + " " +
               QString::fromStdString(f.symbolWithUnit());
    };
    for (const wheel::WheelField& field : wheel::wheelFields()) {
        if (std::string(field.key) == "grouser_height_m")
            form->addRow("<b>Grousers (lugs)</b>", new QWidget(this));
        const auto [decimals, step] = wheelBoxResolution(field);
        auto* box = new ValidatedSpinBox(field, decimals, this);
        box->setObjectName(QString("wheel.") + field.key);
        box->setSingleStep(step);
        form->addRow(label(field), box);
        const std::string key = field.key;
        fields_[key] = box;
        connect(box, &ValidatedSpinBox::editingStarted, document_, &ProjectDocument::endMerge);
        connect(box, &QDoubleSpinBox::editingFinished, document_, &ProjectDocument::endMerge);
        connect(box, &ValidatedSpinBox::messageChanged, message_, &QLabel::setText);
        connect(box, &QDoubleSpinBox::valueChanged, this, [this, key](double v) {
            if (document_->setWheelValue(key, v)) return;
            // Refused: in range on its own but not with the other fields (grousers as high as
            // the radius). Say why, then show the model's value again.
            const std::string problem = document_->wheelValueProblem(key, v);
            refresh();
            message_->setText(QString::fromStdString(problem));
        });
    }
    form->addRow(lug_summary_);
    form->addRow(message_);
    connect(preset_, &QComboBox::currentIndexChanged, this, [this] {
        const std::string name = preset_->currentData().toString().toStdString();
        if (name.empty()) return;
        if (auto wheel = io::resolveWheel(locations_, name)) document_->setWheel(*wheel, name);
    });
    connect(document_, &ProjectDocument::wheelChanged, this, &WheelEditor::refresh);
    connect(document_, &ProjectDocument::changed, message_,
            [this] { clearStaleMessage(message_, this); });
    refresh();
}

WheelEditor::~WheelEditor() { silenceFields(this); }

ValidatedSpinBox* WheelEditor::spinBox(const std::string& key) const {
    const auto it = fields_.find(key);
    return it == fields_.end() ? nullptr : it->second;
}

void WheelEditor::refresh() {
    const Project& project = document_->project();
    selectPreset(preset_, project.wheel_preset,
                 project.wheel_preset.empty() ? project.wheel.name : "");
    for (const wheel::WheelField& field : wheel::wheelFields())
        fields_.at(field.key)->setCommittedValue(field.userValue(project.wheel));
    lug_summary_->setText(lugSummaryText(project.wheel));
    message_->clear();
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
    passUndoShortcuts(slip_angles_);
    message_ = messageLabel(this);
    auto* form = new QFormLayout(this);
    form->addRow(QString("Load %1").arg(QString::fromStdString(load.symbolWithUnit())), load_);
    form->addRow(QString("Slip angles %1").arg(QString::fromStdString(angles.symbolWithUnit())),
                 slip_angles_);
    form->addRow(message_);
    connect(load_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!document_->setLoad(v)) refresh();
    });
    connect(load_, &ValidatedSpinBox::editingStarted, document_, &ProjectDocument::endMerge);
    connect(load_, &QDoubleSpinBox::editingFinished, document_, &ProjectDocument::endMerge);
    connect(load_, &ValidatedSpinBox::messageChanged, message_, &QLabel::setText);
    // Checked at every keystroke (the first bad value named), applied on Enter / focus-out.
    connect(slip_angles_, &QLineEdit::textEdited, this, [this] { checkSlipAngles(); });
    connect(slip_angles_, &QLineEdit::editingFinished, this, [this] {
        const std::optional<std::vector<double>> values = checkSlipAngles();
        if (!values) return;  // flagged in place, not applied
        document_->endMerge();
        if (!document_->setSlipAngles(*values)) refresh();
        slip_angles_->setModified(false);
    });
    connect(document_, &ProjectDocument::conditionsChanged, this, &ConditionsEditor::refresh);
    connect(document_, &ProjectDocument::changed, message_,
            [this] { clearStaleMessage(message_, this); });
    refresh();
}

ConditionsEditor::~ConditionsEditor() { silenceFields(this); }

std::optional<std::vector<double>> ConditionsEditor::checkSlipAngles() {
    const FieldInfo& field = analysis::slipAnglesField();
    std::vector<double> values;
    QString problem;
    for (const QString& part : slip_angles_->text().split(',')) {
        const QString text = part.trimmed();
        bool parsed = false;
        const double v = text.toDouble(&parsed);
        if (text.isEmpty()) {
            problem = "an empty entry between commas";
        } else if (!parsed) {
            problem = QString("\"%1\" is not a number").arg(text);
        } else if (!field.range.contains(v)) {
            problem = QString("β = %1 deg is outside the allowed range %2 deg")
                          .arg(text, QString::fromStdString(field.range.describe()));
        }
        if (!problem.isEmpty()) break;
        values.push_back(v);
    }
    if (slip_angles_->text().trimmed().isEmpty()) problem = "no slip angle given";
    const bool ok = problem.isEmpty();
    QPalette palette = QPalette();
    if (!ok) {
        palette = slip_angles_->palette();
        palette.setColor(QPalette::Base, QColor(255, 222, 222));
        palette.setColor(QPalette::Text, QColor(150, 0, 0));
    }
    slip_angles_->setPalette(palette);
    const QString message =
        ok ? QString()
           : QString("Slip angles: %1; comma-separated angles in %2 deg, not applied")
                 .arg(problem, QString::fromStdString(field.range.describe()));
    slip_angles_->setProperty("invalidMessage", message);
    message_->setText(message);
    if (!ok) return std::nullopt;
    return values;
}

void ConditionsEditor::refresh() {
    const analysis::OperatingConditions& c = document_->project().conditions;
    load_->setCommittedValue(c.load_n);
    QStringList angles;
    for (double beta : c.slip_angles_deg) angles << QString::number(beta);
    slip_angles_->setText(angles.join(", "));
    slip_angles_->setModified(false);
    slip_angles_->setPalette(QPalette());
    slip_angles_->setProperty("invalidMessage", QString());
    message_->clear();
}

}  // namespace terra::ui
