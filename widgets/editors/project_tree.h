#pragma once
/// @file project_tree.h
/// The project tree on the studio's left: soil, wheel, operating conditions, data sets,
/// scenarios and the measured test, each labelled with its current value; selecting an item asks
/// for its editor page.

#include <QTreeWidget>

namespace terra::ui {

class ProjectDocument;

class ProjectTree : public QTreeWidget {
    Q_OBJECT
public:
    /// The editor pages, in the order of the property editor's stack.
    enum Page { kSoil, kWheel, kConditions, kDataSets, kScenarios, kExperiment, kPageCount };

    explicit ProjectTree(ProjectDocument* document, QWidget* parent = nullptr);

signals:
    void pageRequested(int page);

private:
    void refresh();
    ProjectDocument* document_;
    QTreeWidgetItem* items_[kPageCount];
};

}  // namespace terra::ui
