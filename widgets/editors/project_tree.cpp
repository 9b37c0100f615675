#include "widgets/editors/project_tree.h"

#include <QFileInfo>

#include "widgets/document/project_document.h"

namespace terra::ui {

ProjectTree::ProjectTree(ProjectDocument* document, QWidget* parent) : QTreeWidget(parent), document_(document) {
    setHeaderLabels({"Project", "Value"});
    setColumnCount(2);
    const char* names[] = {"Soil", "Wheel", "Operating conditions", "Data sets", "Scenarios"};
    for (int i = 0; i < 5; ++i) {
        items_[i] = new QTreeWidgetItem(this, {names[i]});
        items_[i]->setData(0, Qt::UserRole, i);
    }
    connect(this, &QTreeWidget::currentItemChanged, this, [this](QTreeWidgetItem* item) {
        while (item && item->parent()) item = item->parent();
        if (item) emit pageRequested(item->data(0, Qt::UserRole).toInt());
    });
    connect(document_, &ProjectDocument::changed, this, &ProjectTree::refresh);
    refresh();
    setCurrentItem(items_[kSoil]);
}

void ProjectTree::refresh() {
    const Project& p = document_->project();
    items_[kSoil]->setText(1, QString::fromStdString(p.soil_preset.empty() ? p.soil.name + " (edited)" : p.soil_preset));
    items_[kWheel]->setText(1, QString::fromStdString(p.wheel_preset.empty() ? p.wheel.name + " (edited)" : p.wheel_preset));
    items_[kConditions]->setText(1, QString("W = %1 N").arg(p.conditions.load_n));
    qDeleteAll(items_[kDataSets]->takeChildren());
    for (const std::string& path : p.data_sets) {
        new QTreeWidgetItem(items_[kDataSets], {QFileInfo(QString::fromStdString(path)).fileName()});
    }
    items_[kDataSets]->setText(1, QString::number(p.data_sets.size()));
    items_[kScenarios]->setText(1, p.scenarios.empty() ? "none" : QString::number(p.scenarios.size()));
    expandAll();
    resizeColumnToContents(0);
}

}  // namespace terra::ui
