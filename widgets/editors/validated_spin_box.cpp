#include "widgets/editors/validated_spin_box.h"

#include <QKeyEvent>
#include <QKeySequence>
#include <QLineEdit>
#include <QPalette>
#include <QSignalBlocker>
#include <QTimer>
#include <algorithm>
#include <cmath>
#include <utility>

namespace terra::ui {

ValidatedSpinBox::ValidatedSpinBox(const QString& name, const QString& unit, const Range& range,
                                   int decimals, QWidget* parent)
    : QDoubleSpinBox(parent),
      name_(name),
      label_(unit.isEmpty() ? name : QString("%1 [%2]").arg(name, unit)),
      unit_(unit),
      base_decimals_(decimals),
      range_(range) {
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
    const QString label = QString::fromUtf8(field.label);
    label_ = label.left(1).toUpper() + label.mid(1) + " " +
             QString::fromStdString(field.symbolWithUnit());
    setToolTip(QString("%1 — %2 Allowed: %3")
                   .arg(QString::fromUtf8(field.label), QString::fromUtf8(field.description),
                        QString::fromStdString(field.range.describe())));
}

namespace {

/// Decimals that show `value` exactly (to 1e-9 relative) from `least` up to `most`, but never
/// more than ValidatedSpinBox::kMaxSignificant significant digits (a calibrated k_φ of
/// 2936.28451 showed all five decimals); failing that, to two significant digits (within the
/// same bounds).
int decimalsShowing(double value, int least, int most) {
    if (value == 0.0 || !std::isfinite(value)) return least;
    const int leading = static_cast<int>(std::floor(std::log10(std::abs(value))));
    const int cap = std::clamp(ValidatedSpinBox::kMaxSignificant - 1 - leading, least, most);
    for (int d = least; d <= cap; ++d) {
        const double scale = std::pow(10.0, d);
        if (std::abs(std::round(value * scale) / scale - value) <= 1e-9 * std::abs(value)) return d;
    }
    return std::clamp(1 - leading, least, most);
}

}  // namespace

void ValidatedSpinBox::setCommittedValue(double value) {
    const bool had_message = !valid_ || !property("rejectedMessage").toString().isEmpty();
    {
        const QSignalBlocker block(this);
        const int decimals = decimalsShowing(value, base_decimals_, kMaxDecimals);
        if (decimals != this->decimals()) setDecimals(decimals);
        last_text_ = textFromValue(value);
        setValue(value);
        committed_ = this->value();
        flag(true, {});
    }
    if (had_message) emit messageChanged({});  // outside the blocker: the editor's line clears
}

void ValidatedSpinBox::applyPendingDecimals() {
    const int needed = std::exchange(pending_decimals_, 0);
    if (needed <= decimals()) return;
    // The text as it is now (keys typed since included), put back after the change.
    const QString typed = lineEdit()->text();
    const int cursor = lineEdit()->cursorPosition();
    {
        const QSignalBlocker block(this);
        setDecimals(needed);  // rewrites the text from the committed value
    }
    lineEdit()->setText(typed);  // validated again: acceptable now
    lineEdit()->setCursorPosition(cursor);
    debounce_->start();  // committed as if typed
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
    if (event->key() == Qt::Key_Return || event->key() == Qt::Key_Enter) {
        applyPendingDecimals();  // typed decimals taken before Enter commits the text
        debounce_->stop();
    }
    if ((event->key() == Qt::Key_Return || event->key() == Qt::Key_Enter) && !valid_) {
        revertIfInvalid();
        event->accept();
        return;
    }
    QDoubleSpinBox::keyPressEvent(event);
}

void ValidatedSpinBox::focusInEvent(QFocusEvent* event) {
    emit editingStarted();
    QDoubleSpinBox::focusInEvent(event);
}

void ValidatedSpinBox::focusOutEvent(QFocusEvent* event) {
    applyPendingDecimals();
    debounce_->stop();  // QAbstractSpinBox commits acceptable text on focus-out itself
    revertIfInvalid();
    QDoubleSpinBox::focusOutEvent(event);
}

bool ValidatedSpinBox::event(QEvent* event) {
    // The line edit inside claims Ctrl+Z / Ctrl+Y for its own text undo, so the studio's Undo did
    // nothing while the cursor was in a field. Text typed but not yet committed is dropped (that
    // is the undo the user sees); otherwise the shortcut goes on to the document's undo stack.
    if (event->type() == QEvent::ShortcutOverride) {
        auto* key = static_cast<QKeyEvent*>(event);
        const bool undo = key->matches(QKeySequence::Undo);
        const bool redo = key->matches(QKeySequence::Redo) ||
                          QKeySequence(key->keyCombination()) == QKeySequence(Qt::CTRL | Qt::Key_Y);
        if (undo || redo) {
            debounce_->stop();
            if (undo && (!valid_ || textFromValue(committed_) != cleanText())) {
                setCommittedValue(committed_);
                event->accept();  // consumed here: typing dropped, the document untouched
                return true;
            }
            event->ignore();  // not overridden: the window's Undo/Redo shortcut fires
            return true;
        }
    }
    return QDoubleSpinBox::event(event);
}

QValidator::State ValidatedSpinBox::validate(QString& text, int& pos) const {
    const QValidator::State state = QDoubleSpinBox::validate(text, pos);
    QString number = text;
    if (!suffix().isEmpty()) number.chop(suffix().size());
    number = number.trimmed();
    bool parsed = false;
    const double value = locale().toDouble(number, &parsed);
    const QString allowed = QString("allowed %1%2")
                                .arg(QString::fromStdString(range_.describe()),
                                     unit_.isEmpty() ? QString() : " " + unit_);
    if (state == QValidator::Acceptable ||
        (!specialValueText().isEmpty() && text == specialValueText())) {
        last_text_ = number;
        flag(true, {});
        return state;
    }
    if (parsed && range_.contains(value) && value >= minimum() && value <= maximum()) {
        // In range, with more decimals than the box shows now (Qt refuses those). Up to
        // kMaxDecimals the box takes them, as it shows a value from a file (0.00234): once this
        // validation has returned, the decimals are raised and the typed text put back.
        last_text_ = number;
        // The decimals the value needs, or that were typed ("1.500" is 1.5, typed with three).
        const qsizetype point = number.indexOf(locale().decimalPoint());
        qsizetype typed = 0;
        while (point >= 0 && point + 1 + typed < number.size() &&
               number[point + 1 + typed].isDigit())
            ++typed;
        const int needed = std::min(
            std::max(decimalsShowing(value, base_decimals_, kMaxDecimals), static_cast<int>(typed)),
            kMaxDecimals);
        if (needed > decimals()) {
            auto* self = const_cast<ValidatedSpinBox*>(this);
            self->pending_decimals_ = std::max(pending_decimals_, needed);
            QTimer::singleShot(0, self, [self] { self->applyPendingDecimals(); });
            flag(true, {});
            return QValidator::Intermediate;
        }
        // Beyond kMaxDecimals: said as such, not as out of range ("c = 0.0023 kPa is outside
        // [0, 200]" was false).
        flag(false, QString("%1 = %2 %3: this field keeps %4 decimals (it would be %5)")
                        .arg(name_, number, unit_)
                        .arg(decimals())
                        .arg(locale().toString(value, 'f', decimals()))
                        .simplified());
        return QValidator::Intermediate;
    }
    if (parsed) {
        // Out of range: keep the whole text on screen ("75", not the "7" a refused keystroke
        // leaves), flagged with the range; it is never committed (revertIfInvalid()).
        last_text_ = number;
        flag(false, QString("%1 = %2 %3 is outside the allowed range %4")
                        .arg(name_, QString::number(value), unit_,
                             QString::fromStdString(range_.describe()))
                        .simplified());
        return QValidator::Intermediate;
    }
    if (number.isEmpty() || number == "-" || number == "+" || number.endsWith('e') ||
        number.endsWith('E') || number == locale().decimalPoint()) {
        last_text_ = number;
        flag(true, {});  // the start of a number: wait for the rest
        return QValidator::Intermediate;
    }
    if (!specialValueText().isEmpty() && specialValueText().startsWith(number)) return state;
    // Not a number: the keystroke is refused, and the field says why (it used to do nothing). The
    // message names the field by its label and the key as a key: "c: \"c\" is not a number" in
    // the cohesion field read as if the field were not a number.
    qsizetype head = 0, tail = 0;
    while (head < number.size() && head < last_text_.size() && number[head] == last_text_[head])
        ++head;
    while (tail < number.size() - head && tail < last_text_.size() - head &&
           number[number.size() - 1 - tail] == last_text_[last_text_.size() - 1 - tail])
        ++tail;
    const QString typed = number.mid(head, number.size() - head - tail);
    const QString refused = typed.isEmpty() ? number : typed;
    auto* self = const_cast<ValidatedSpinBox*>(this);
    const QString message =
        QString("%1 takes a number: the %2 \"%3\" was not accepted (%4)")
            .arg(label_, refused.size() == 1 ? "key" : "text", refused, allowed);
    self->setProperty("rejectedMessage", message);
    emit self->messageChanged(message);
    return QValidator::Invalid;
}

void ValidatedSpinBox::flag(bool valid, const QString& message) const {
    auto* self = const_cast<ValidatedSpinBox*>(this);
    if (valid && !property("rejectedMessage").toString().isEmpty()) {
        self->setProperty("rejectedMessage", QString());
        if (valid_) emit self->messageChanged({});
    }
    if (valid == valid_) {
        if (!valid && message != property("invalidMessage").toString()) {
            self->lineEdit()->setToolTip(message);
            self->setProperty("invalidMessage", message);
            emit self->messageChanged(message);
        }
        return;
    }
    valid_ = valid;
    // A tinted background, not a style-sheet border: a border changes the box's size hint and
    // shifted every row below by a few pixels while the field was red.
    if (valid) {
        self->setPalette(QPalette());
    } else {
        QPalette palette = self->palette();
        palette.setColor(QPalette::Base, QColor(255, 222, 222));
        palette.setColor(QPalette::Text, QColor(150, 0, 0));
        self->setPalette(palette);
    }
    self->lineEdit()->setToolTip(valid ? QString() : message);
    self->setProperty("invalidMessage", valid ? QString() : message);
    emit self->messageChanged(valid ? QString() : message);
}

}  // namespace terra::ui
