#pragma once
/// @file validated_spin_box.h
/// A spin box for one range-checked field: typed text outside the allowed range is flagged at the
/// field (red frame, tooltip naming the value and the range) and never committed — the spin box
/// reverts to the last valid value when editing ends. Typing is live but debounced: once the
/// text has been acceptable and unchanged for debounceMs(), it is committed (valueChanged) as if
/// Enter had been pressed; arrows, wheel, Enter and focus-out commit at once. A number out of range
/// stays on screen whole, tinted, with messageChanged() naming the range; a keystroke that cannot
/// make a number ("abc") is refused with a message.

#include <QDoubleSpinBox>

class QTimer;

#include "core/common/field.h"
#include "core/common/range.h"

namespace terra::ui {

class ValidatedSpinBox : public QDoubleSpinBox {
    Q_OBJECT
public:
    /// `name` and `unit` are used in the message ("φ = 75 deg is outside [0, 60)").
    ValidatedSpinBox(const QString& name, const QString& unit, const Range& range, int decimals,
                     QWidget* parent = nullptr);
    /// For a field of a field table: its symbol, unit and range, its description as the tooltip.
    ValidatedSpinBox(const FieldInfo& field, int decimals, QWidget* parent = nullptr);

    const Range& allowedRange() const { return range_; }
    /// Whether the text being typed is acceptable (false while flagged).
    bool textIsValid() const { return valid_; }

    QValidator::State validate(QString& text, int& pos) const override;

    /// Shows a value that came from the model, without emitting valueChanged: with more decimals
    /// than the box's own when it needs them (c = 0.0023 kPa was shown as "0.00"), at most
    /// kMaxDecimals and kMaxSignificant significant digits, to two significant digits (or the
    /// box's own decimals) when it cannot be shown exactly within them. Only the text is
    /// shortened: the model keeps its value.
    void setCommittedValue(double value);
    static constexpr int kMaxDecimals = 6;
    static constexpr int kMaxSignificant = 6;

    /// Quiet time after the last keystroke before typed text is committed [ms].
    static constexpr int kDebounceMs = 300;
    int debounceMs() const { return kDebounceMs; }

signals:
    /// What is wrong with the text being typed (the value and the allowed range, or "not a
    /// number"); empty when it is fine again. Editors show it under the fields.
    void messageChanged(const QString& message);
    /// The field got the focus: typing in it is a new undo step (ProjectDocument::endMerge()).
    void editingStarted();

protected:
    /// Enter or leaving the field with flagged text restores the last committed value: a
    /// half-typed prefix ("7" of "75") is never committed either.
    void keyPressEvent(QKeyEvent* event) override;
    void focusInEvent(QFocusEvent* event) override;
    void focusOutEvent(QFocusEvent* event) override;
    /// Ctrl+Z / Ctrl+Y reach the studio's undo stack with the cursor in the field.
    bool event(QEvent* event) override;

private:
    void revertIfInvalid();
    void commitTyped();
    void flag(bool valid, const QString& message) const;

    QString name_;
    QString label_;  // "Cohesion c [kPa]" for a field's box: who the messages speak of
    QString unit_;
    int base_decimals_ = 2;
    mutable QString last_text_;  // the last text accepted while typing (a refused key is the rest)
    Range range_;
    mutable bool valid_ = true;
    double committed_ = 0.0;
    QTimer* debounce_;
    /// Typed decimals the box takes (validate() found them in range): raised once the validation
    /// has returned, or at Enter or focus-out, whichever comes first.
    int pending_decimals_ = 0;
    void applyPendingDecimals();
};

}  // namespace terra::ui
