#pragma once
/// @file help_dialog.h
/// The studio's in-app help: the user guide (docs/user-guide.md, rendered as Markdown) and the
/// keyboard shortcuts, taken from the window's actions so the list cannot drift from the menus.

#include <QDialog>
#include <QList>
#include <QString>

class QAction;
class QTabWidget;
class QTableWidget;
class QTextBrowser;

namespace terra::ui {

class HelpDialog : public QDialog {
    Q_OBJECT
public:
    /// `guide` is the Markdown file shown (a missing file is said so in the page itself);
    /// `actions` are listed with their shortcuts (those without one are left out).
    HelpDialog(const QString& guide, const QList<QAction*>& actions, QWidget* parent = nullptr);

    void showGuide();
    void showShortcuts();
    QTextBrowser* guideView() const { return guide_; }
    QTableWidget* shortcutTable() const { return shortcuts_; }

private:
    QTabWidget* tabs_;
    QTextBrowser* guide_;
    QTableWidget* shortcuts_;
};

}  // namespace terra::ui
