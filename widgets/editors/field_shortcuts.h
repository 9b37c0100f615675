#pragma once
/// @file field_shortcuts.h
/// The window's shortcuts work with the cursor in a field. Qt's text fields keep a few keys for
/// themselves — under X11's key bindings Ctrl+E moves to the end of the line — so Ctrl+E (Export
/// Plot) did nothing from a field, and a file name typed next went into the field. A key that
/// one of the window's actions owns now goes to the action, except the keys a field edits with:
/// undo and redo (the fields pass them on themselves when nothing is typed, validated_spin_box.h),
/// cut, copy, paste and select all. The same in a dock of the window torn off into a window of its
/// own (the window's actions are application shortcuts, main_window_menus.cpp).

class QWidget;

namespace terra::ui {

/// For every text field and spin box of `window` (installed once, on the application: the
/// fields get the key first; removed with the window).
void passWindowShortcutsThroughFields(QWidget* window);

}  // namespace terra::ui
