#include "widgets/editors/field_shortcuts.h"

#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QKeyEvent>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPointer>
#include <QTextEdit>

namespace terra::ui {
namespace {

bool isTextField(const QObject* object) {
    return qobject_cast<const QLineEdit*>(object) ||
           qobject_cast<const QAbstractSpinBox*>(object) ||
           qobject_cast<const QPlainTextEdit*>(object) || qobject_cast<const QTextEdit*>(object);
}

/// Keys a field edits with: they stay the field's.
bool isEditingKey(const QKeyEvent& key) {
    for (const QKeySequence::StandardKey standard :
         {QKeySequence::Undo, QKeySequence::Redo, QKeySequence::Cut, QKeySequence::Copy,
          QKeySequence::Paste, QKeySequence::SelectAll}) {
        if (key.matches(standard)) return true;
    }
    return QKeySequence(key.keyCombination()) == QKeySequence(Qt::CTRL | Qt::Key_Y);
}

class FieldShortcuts : public QObject {
public:
    explicit FieldShortcuts(QWidget* window) : QObject(window), window_(window) {}

    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() != QEvent::ShortcutOverride || !window_ || !isTextField(watched))
            return false;
        const auto* widget = static_cast<QWidget*>(watched);
        if (!inWindow(*widget)) return false;  // a dialog's fields keep their keys
        const auto* key = static_cast<QKeyEvent*>(event);
        if (isEditingKey(*key)) return false;
        const QKeySequence sequence(key->keyCombination());
        for (const QAction* action : window_->findChildren<QAction*>()) {
            if (action->isEnabled() && action->shortcuts().contains(sequence)) {
                event->ignore();  // not the field's: the window's shortcut fires
                return true;
            }
        }
        return false;
    }

private:
    /// In the window, or in one of its docks torn off into a window of its own.
    bool inWindow(const QWidget& widget) const {
        const QWidget* top = widget.window();
        if (top == window_) return true;
        if (!qobject_cast<const QDockWidget*>(top)) return false;
        for (const QWidget* w = top->parentWidget(); w != nullptr; w = w->parentWidget()) {
            if (w == window_) return true;
        }
        return false;
    }

    QPointer<QWidget> window_;
};

}  // namespace

void passWindowShortcutsThroughFields(QWidget* window) {
    qApp->installEventFilter(new FieldShortcuts(window));
}

}  // namespace terra::ui
