#include "widgets/help/help_dialog.h"

#include <QAction>
#include <QDialogButtonBox>
#include <QFile>
#include <QFileInfo>
#include <QHeaderView>
#include <QKeySequence>
#include <QTabWidget>
#include <QTableWidget>
#include <QTextBrowser>
#include <QVBoxLayout>

namespace terra::ui {

HelpDialog::HelpDialog(const QString& guide, const QList<QAction*>& actions, QWidget* parent)
    : QDialog(parent) {
    setWindowTitle("TerraStudio help");
    tabs_ = new QTabWidget(this);
    guide_ = new QTextBrowser(tabs_);
    guide_->setObjectName("help.guide");
    guide_->setOpenExternalLinks(true);
    QFile file(guide);
    if (file.open(QIODevice::ReadOnly)) {
        // Relative links and images of the guide resolve beside it (docs/images).
        guide_->setSearchPaths({QFileInfo(guide).absolutePath()});
        guide_->setMarkdown(QString::fromUtf8(file.readAll()));
    } else {
        guide_->setPlainText(
            QString("The user guide is not installed where it is expected (%1). It is "
                    "docs/user-guide.md of the source tree.")
                .arg(guide));
    }
    shortcuts_ = new QTableWidget(0, 2, tabs_);
    shortcuts_->setObjectName("help.shortcuts");
    shortcuts_->setHorizontalHeaderLabels({"Shortcut", "Action"});
    shortcuts_->verticalHeader()->hide();
    shortcuts_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    shortcuts_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
    shortcuts_->horizontalHeader()->setStretchLastSection(true);
    for (const QAction* action : actions) {
        if (action->shortcuts().isEmpty()) continue;
        QStringList keys;
        for (const QKeySequence& key : action->shortcuts())
            keys << key.toString(QKeySequence::NativeText);
        const int row = shortcuts_->rowCount();
        shortcuts_->insertRow(row);
        shortcuts_->setItem(row, 0, new QTableWidgetItem(keys.join(", ")));
        shortcuts_->setItem(row, 1, new QTableWidgetItem(action->text().remove('&')));
    }
    tabs_->addTab(guide_, "User guide");
    tabs_->addTab(shortcuts_, "Keyboard shortcuts");
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(tabs_, 1);
    layout->addWidget(buttons);
    resize(760, 560);
}

void HelpDialog::showGuide() { tabs_->setCurrentWidget(guide_); }

void HelpDialog::showShortcuts() { tabs_->setCurrentWidget(shortcuts_); }

}  // namespace terra::ui
