#include "widgets/editors/preset_names.h"

#include <QAbstractItemView>
#include <QComboBox>
#include <QCoreApplication>
#include <cstring>

namespace terra::ui {
namespace {

constexpr int kPresetBoxCharacters = 14;  // "sandy loam (edited)" nearly whole

}  // namespace

io::PresetLocations studioPresetLocations() {
    return io::PresetLocations::standard(QCoreApplication::applicationDirPath().toStdString());
}

QString presetDisplayName(const io::PresetLocations& locations, const char* kind,
                          const std::string& id) {
    std::string name;
    if (std::strcmp(kind, "soils") == 0) {
        if (const auto soil = io::resolveSoil(locations, id)) name = soil->name;
    } else if (std::strcmp(kind, "wheels") == 0) {
        if (const auto wheel = io::resolveWheel(locations, id)) name = wheel->name;
    }
    return QString::fromStdString(name.empty() ? id : name);
}

void addPresetItems(QComboBox* box, const io::PresetLocations& locations, const char* kind) {
    for (const std::string& id : io::presetNames(locations, kind)) {
        const QString text = QString::fromStdString(id);
        box->addItem(presetDisplayName(locations, kind, id), text);
        box->setItemData(box->count() - 1, "Preset " + text, Qt::ToolTipRole);
    }
    // Names are longer than ids ("KLS-1 lunar soil simulant (relative density 60 %)"): the box
    // must not widen its panel past a 1024 px screen; its list shows them whole.
    box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    box->setMinimumContentsLength(kPresetBoxCharacters);
    box->view()->setMinimumWidth(box->view()->sizeHintForColumn(0) + 24);
}

}  // namespace terra::ui
