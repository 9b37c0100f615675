#include "widgets/editors/validated_spin_box.h"

#include <QKeyEvent>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QTimer>
#include <cmath>

namespace terra::ui {

ValidatedSpinBox::ValidatedSpinBox(const QString& name, const QString& unit, const Range& range,
                                   int decimals, QWidget* parent)
    : QDoubleSpinBox(parent), name_(name), unit_(unit), range_(range) {
    setDecimals(decimals);
    const double step = std::pow(10.0, -decimals);
    // Open ends: the nearest value the box can show inside the range.
    setRange(range.low_open ? range.low + step : range.low,
             range.high_open ? range.high - step : range.high);
    // Keystrokes do not emit valueChanged themselves: a settled, acceptable text is committed by
    // the debounce timer (or at once by Enter / focus-out), so "3" of "35" never reaches the model
    // while the user is still typing, and a settled edit is one (merged) undo command.
    setKeyboardTracking(false);
    debounce_ = new QTimer(this);
    debounce_->setSingleShot(true);
    debounce_->setInterval(kDebounceMs);
    connect(debounce_, &QTimer::timeout, this, &ValidatedSpinBox::commitTyped);
    connect(lineEdit(), &QLineEdit::textEdited, debounce_, qOverload<>(&QTimer::start));
    setAccelerated(true);
    setToolTip(
        QString("%1 [%2], allowed %3").arg(name, unit, QString::fromStdString(range.describe())));
    setCorrectionMode(QAbstractSpinBox::CorrectToPreviousValue);
    connect(this, &QDoubleSpinBox::valueChanged, this, [this](double v) { committed_ = v; });
}

ValidatedSpinBox::ValidatedSpinBox(const FieldInfo& field, int decimals, QWidget* parent)
    : ValidatedSpinBox(QString::fromUtf8(field.symbol), QString::fromStdString(field.displayUnit()),
                       field.range, decimals, parent) {
    setToolTip(QString("%1 — %2 Allowed: %3")
                   .arg(QString::fromUtf8(field.label), QString::fromUtf8(field.description),
                        QString::fromStdString(field.range.describe())));
}

void ValidatedSpinBox::setCommittedValue(double value) {
    const QSignalBlocker block(this);
    setValue(value);
    committed_ = this->value();
    flag(true, {});
}

void ValidatedSpinBox::commitTyped() {
    if (!valid_ || !hasAcceptableInput()) return;  // flagged or intermediate ("", "-", "1e"): wait
    interpretText();  // emits valueChanged when the value differs from the shown one
}

void ValidatedSpinBox::revertIfInvalid() {
    if (valid_) return;
    setCommittedValue(committed_);
}

void ValidatedSpinBox::keyPressEvent(QKeyEvent* event) {
    if (event->key() == Qt::Key_Return || event->key() == Qt::Key_Enter) debounce_->stop();
    if ((event->key() == Qt::Key_Return || event->key() == Qt::Key_Enter) && !valid_) {
        revertIfInvalid();
        event->accept();
        return;
    }
    QDoubleSpinBox::keyPressEvent(event);
}

void ValidatedSpinBox::focusOutEvent(QFocusEvent* event) {
    debounce_->stop();  // QAbstractSpinBox commits acceptable text on focus-out itself
    revertIfInvalid();
    QDoubleSpinBox::focusOutEvent(event);
}

QValidator::State ValidatedSpinBox::validate(QString& text, int& pos) const {
    const QValidator::State state = QDoubleSpinBox::validate(text, pos);
    QString number = text;
    if (!suffix().isEmpty()) number.chop(suffix().size());
    bool parsed = false;
    const double value = locale().toDouble(number.trimmed(), &parsed);
    if (state == QValidator::Acceptable ||
        (!specialValueText().isEmpty() && text == specialValueText())) {
        flag(true, {});
    } else if (parsed) {
        flag(false, QString("%1 = %2 %3 is outside the allowed range %4")
                        .arg(name_, QString::number(value), unit_,
                             QString::fromStdString(range_.describe())));
    } else {
        flag(false, QString("%1: \"%2\" is not a number").arg(name_, number));
    }
    return state;
}

void ValidatedSpinBox::flag(bool valid, const QString& message) const {
    if (valid == valid_) return;
    valid_ = valid;
    auto* self = const_cast<ValidatedSpinBox*>(this);
    self->setStyleSheet(valid ? QString()
                              : QString("QDoubleSpinBox { border: 2px solid #d62728; }"));
    self->lineEdit()->setToolTip(valid ? QString() : message);
    self->setProperty("invalidMessage", valid ? QString() : message);
}

}  // namespace terra::ui
