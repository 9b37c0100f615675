#include "widgets/editors/project_tree.h"

#include <QFileInfo>
#include <QHeaderView>
#include <QTreeWidgetItemIterator>

#include "widgets/document/project_document.h"

namespace terra::ui {

ProjectTree::ProjectTree(ProjectDocument* document, QWidget* parent)
    : QTreeWidget(parent), document_(document) {
    setHeaderLabels({"Project", "Value"});
    setColumnCount(2);
    // The names take what they need, the values the rest (they were cut to "sandy l…").
    header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
    header()->setStretchLastSection(true);
    header()->setMinimumSectionSize(40);
    const char* names[] = {"Soil",      "Wheel",     "Operating conditions",
                           "Data sets", "Scenarios", "Measured test"};
    for (int i = 0; i < kPageCount; ++i) {
        items_[i] = new QTreeWidgetItem(this, {names[i]});
        items_[i]->setData(0, Qt::UserRole, i);
    }
    connect(this, &QTreeWidget::currentItemChanged, this, [this](QTreeWidgetItem* item) {
        while (item && item->parent()) item = item->parent();
        if (item) emit pageRequested(item->data(0, Qt::UserRole).toInt());
    });
    connect(document_, &ProjectDocument::changed, this, &ProjectTree::refresh);
    // Panel settings (the rover panel's edited scenarios) change without changed().
    connect(document_, &ProjectDocument::panelSettingsChanged, this, &ProjectTree::refresh);
    refresh();
    setCurrentItem(items_[kSoil]);
}

namespace {

// A soil or wheel that is no longer its preset: its name, said to be edited unless the name
// already qualifies itself ("sandy loam (edited)", "… (calibrated)": no "(edited) (edited)").
QString notPresetLabel(const std::string& name) {
    const QString text = QString::fromStdString(name);
    return text.endsWith(')') ? text : text + " (edited)";
}

}  // namespace

void ProjectTree::refresh() {
    const Project& p = document_->project();
    // A preset by its name ("sandy loam"), its file id ("sandy-loam") in the tooltip.
    auto label = [](const std::string& preset, const std::string& name) {
        if (preset.empty()) return notPresetLabel(name);
        return QString::fromStdString(name.empty() ? preset : name);
    };
    items_[kSoil]->setText(1, label(p.soil_preset, p.soil.name));
    items_[kWheel]->setText(1, label(p.wheel_preset, p.wheel.name));
    items_[kConditions]->setText(1, QString("W = %1 N").arg(p.conditions.load_n));
    qDeleteAll(items_[kDataSets]->takeChildren());
    for (const std::string& path : p.data_sets) {
        new QTreeWidgetItem(items_[kDataSets],
                            {QFileInfo(QString::fromStdString(path)).fileName()});
    }
    items_[kDataSets]->setText(1, QString::number(p.data_sets.size()));
    // Scenario files of the project plus the scenarios edited in the rover panel (kept in its
    // settings, "edited": {name: scenario}).
    qDeleteAll(items_[kScenarios]->takeChildren());
    int scenario_count = 0;
    for (const std::string& path : p.scenarios) {
        new QTreeWidgetItem(items_[kScenarios],
                            {QFileInfo(QString::fromStdString(path)).fileName()});
        ++scenario_count;
    }
    const auto rover = p.panels.find("rover");
    if (rover != p.panels.end() && rover->is_object() && rover->contains("edited") &&
        (*rover)["edited"].is_object()) {
        for (const auto& edited : (*rover)["edited"].items()) {
            new QTreeWidgetItem(items_[kScenarios],
                                {QString::fromStdString(edited.key()), "edited"});
            ++scenario_count;
        }
    }
    items_[kScenarios]->setText(
        1, scenario_count == 0 ? "shipped only" : QString::number(scenario_count));
    const QString test = QString::fromStdString(p.experiment);
    items_[kExperiment]->setText(1, test.isEmpty() ? QString("none") : QFileInfo(test).fileName());
    // Whatever does not fit is in the tooltip.
    for (QTreeWidgetItemIterator it(this); *it; ++it) {
        (*it)->setToolTip(0, (*it)->text(0));
        (*it)->setToolTip(1, (*it)->text(1));
    }
    for (const auto& [row, preset] : {std::pair{kSoil, p.soil_preset}, {kWheel, p.wheel_preset}}) {
        if (!preset.empty())
            items_[row]->setToolTip(
                1, items_[row]->text(1) + " (preset " + QString::fromStdString(preset) + ")");
    }
    expandAll();
    resizeColumnToContents(0);
}

}  // namespace terra::ui
