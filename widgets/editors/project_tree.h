#pragma once
/// @file project_tree.h
/// The project tree on the studio's left: soil, wheel, operating conditions, data sets and
/// scenarios, each labelled with its current value; selecting an item asks for its editor.

#include <QTreeWidget>

namespace terra::ui {

class ProjectDocument;

class ProjectTree : public QTreeWidget {
    Q_OBJECT
public:
    /// The editor pages, in the order of the property editor's stack.
    enum Page { kSoil, kWheel, kConditions, kDataSets, kScenarios };

    explicit ProjectTree(ProjectDocument* document, QWidget* parent = nullptr);

signals:
    void pageRequested(int page);

private:
    void refresh();
    ProjectDocument* document_;
    QTreeWidgetItem* items_[5];
};

}  // namespace terra::ui
