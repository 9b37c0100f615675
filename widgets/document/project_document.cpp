#include "widgets/document/project_document.h"

#include <QSaveFile>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "core/common/range.h"

namespace terra::ui {
namespace {

/// Undo and redo both call one setter of the document with the value to install.
template <typename T>
class SetValueCommand : public QUndoCommand {
public:
    SetValueCommand(const QString& text, int merge_id, T before, T after,
                    std::function<void(const T&)> apply)
        : QUndoCommand(text),
          merge_id_(merge_id),
          before_(std::move(before)),
          after_(std::move(after)),
          apply_(std::move(apply)) {}
    void undo() override { apply_(before_); }
    void redo() override { apply_(after_); }
    int id() const override { return merge_id_; }
    bool mergeWith(const QUndoCommand* other) override {
        // Same id implies same field and type: a drag of one slider becomes one undo step.
        after_ = static_cast<const SetValueCommand*>(other)->after_;
        return true;
    }

private:
    int merge_id_;
    T before_, after_;
    std::function<void(const T&)> apply_;
};

// Merge ids: one per field; -1 (no merging) for whole-object replacements.
constexpr int kSoilFieldIdBase = 100;
constexpr int kWheelRadiusId = 200, kWheelWidthId = 201, kLoadId = 300, kSlipAnglesId = 301,
              kModelId = 302;

}  // namespace

ProjectDocument::ProjectDocument(QObject* parent) : QObject(parent), undo_(new QUndoStack(this)) {
    connect(undo_, &QUndoStack::cleanChanged, this,
            [this](bool) { emit modifiedChanged(isModified()); });
}

bool ProjectDocument::isModified() const { return !undo_->isClean() || settings_modified_; }

void ProjectDocument::notify(Part part) {
    ++revision_;
    switch (part) {
        case Part::kSoil:
            emit soilChanged();
            break;
        case Part::kWheel:
            emit wheelChanged();
            break;
        case Part::kConditions:
            emit conditionsChanged();
            break;
        case Part::kDataSets:
            emit dataSetsChanged();
            break;
    }
    emit changed();
}

template <typename T>
bool ProjectDocument::pushField(const QString& text, int merge_id, Part part, T* field,
                                const T& value) {
    if (*field == value) return true;
    undo_->push(
        new SetValueCommand<T>(text, merge_id, *field, value, [this, field, part](const T& v) {
            *field = v;
            notify(part);
        }));
    return true;
}

template <typename T>
bool ProjectDocument::push(const QString& text, int merge_id, Part part, T Project::*member,
                           const T& value) {
    return pushField(text, merge_id, part, &(project_.*member), value);
}

bool ProjectDocument::setSoilValue(const std::string& key, double user_value) {
    const auto fields = soil::soilFields();
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const soil::SoilField& field = fields[i];
        if (key != field.key) continue;
        if (!field.range.contains(user_value)) return false;
        double& member = project_.soil.*(field.member);
        if (roundSignificant(soil::userValue(project_.soil, field)) == roundSignificant(user_value))
            return true;
        soil::SoilParameters candidate = project_.soil;
        soil::setUserValue(candidate, field, user_value);
        if (!soil::validate(candidate).empty()) return false;
        return pushField(QString("Set %1 = %2 %3")
                             .arg(QString::fromUtf8(field.symbol))
                             .arg(user_value)
                             .arg(QString::fromStdString(field.displayUnit())),
                         kSoilFieldIdBase + static_cast<int>(i), Part::kSoil, &member,
                         candidate.*(field.member));
    }
    return false;
}

bool ProjectDocument::setWheelValue(const std::string& key, double metres) {
    const wheel::WheelField* field = wheel::findWheelField(key);
    if (!field || !field->range.contains(metres)) return false;
    const bool radius = field == &wheel::radiusField();
    return pushField(QString("Set wheel %1 = %2 %3")
                         .arg(QString::fromUtf8(field->symbol))
                         .arg(metres)
                         .arg(QString::fromUtf8(field->unit)),
                     radius ? kWheelRadiusId : kWheelWidthId, Part::kWheel,
                     &(project_.wheel.*field->member), field->toSi(metres));
}

bool ProjectDocument::setLoad(double load_n) {
    const FieldInfo& field = contact::loadField();
    if (!field.range.contains(load_n)) return false;
    return pushField(QString("Set load %1 = %2 %3")
                         .arg(QString::fromUtf8(field.symbol))
                         .arg(load_n)
                         .arg(QString::fromUtf8(field.unit)),
                     kLoadId, Part::kConditions, &project_.conditions.load_n, load_n);
}

bool ProjectDocument::setSlipAngles(const std::vector<double>& slip_angles_deg) {
    if (slip_angles_deg.empty()) return false;
    for (double beta : slip_angles_deg) {
        if (!analysis::slipAnglesField().range.contains(beta)) return false;
    }
    return pushField(QString("Set slip angles"), kSlipAnglesId, Part::kConditions,
                     &project_.conditions.slip_angles_deg, slip_angles_deg);
}

bool ProjectDocument::setQuadraticModel(bool quadratic) {
    return pushField(QString(quadratic ? "Use quadratic model" : "Use full model"), kModelId,
                     Part::kConditions, &project_.conditions.quadratic, quadratic);
}

bool ProjectDocument::setSoil(const soil::SoilParameters& soil, const std::string& preset) {
    if (!soil::validate(soil).empty()) return false;
    using Pair = std::pair<soil::SoilParameters, std::string>;
    const Pair before{project_.soil, project_.soil_preset}, after{soil, preset};
    if (io::toJson(before.first) == io::toJson(after.first) && before.second == after.second)
        return true;
    undo_->push(
        new SetValueCommand<Pair>(QString("Soil preset %1").arg(QString::fromStdString(preset)), -1,
                                  before, after, [this](const Pair& v) {
                                      project_.soil = v.first;
                                      project_.soil_preset = v.second;
                                      notify(Part::kSoil);
                                  }));
    return true;
}

bool ProjectDocument::setWheel(const wheel::WheelParameters& wheel, const std::string& preset) {
    if (!wheel::validate(wheel).empty()) return false;
    using Pair = std::pair<wheel::WheelParameters, std::string>;
    const Pair before{project_.wheel, project_.wheel_preset}, after{wheel, preset};
    if (io::toJson(before.first) == io::toJson(after.first) && before.second == after.second)
        return true;
    undo_->push(
        new SetValueCommand<Pair>(QString("Wheel preset %1").arg(QString::fromStdString(preset)),
                                  -1, before, after, [this](const Pair& v) {
                                      project_.wheel = v.first;
                                      project_.wheel_preset = v.second;
                                      notify(Part::kWheel);
                                  }));
    return true;
}

bool ProjectDocument::addDataSet(const std::string& path) {
    std::vector<std::string> sets = project_.data_sets;
    if (std::find(sets.begin(), sets.end(), path) != sets.end()) return true;
    sets.push_back(path);
    return pushField(QString("Add data set"), -1, Part::kDataSets, &project_.data_sets, sets);
}

void ProjectDocument::setPanelSettings(const std::string& panel, const nlohmann::json& settings) {
    if (project_.panels.contains(panel) && project_.panels[panel] == settings) return;
    project_.panels[panel] = settings;
    // Not undoable, but saved with the project (an edited scenario lives here): unsaved, it must
    // make the close ask and the autosave run like any other change.
    const bool was_modified = isModified();
    settings_modified_ = true;
    if (!was_modified) emit modifiedChanged(true);
    emit panelSettingsChanged();
}

void ProjectDocument::reset(const Project& project, const QString& file_path) {
    project_ = project;
    settings_modified_ = false;
    undo_->clear();
    undo_->setClean();
    file_path_ = file_path;
    emit filePathChanged(file_path_);
    for (Part part : {Part::kSoil, Part::kWheel, Part::kConditions, Part::kDataSets}) notify(part);
    emit modifiedChanged(false);
}

bool ProjectDocument::save(const QString& path, QString* error) {
    QSaveFile file(path);
    const std::string text = toJson(project_).dump(2) + "\n";
    if (!file.open(QIODevice::WriteOnly) ||
        file.write(text.data(), static_cast<qint64>(text.size())) !=
            static_cast<qint64>(text.size()) ||
        !file.commit()) {
        if (error) *error = QString("cannot save %1: %2").arg(path, file.errorString());
        return false;
    }
    if (!path.endsWith(".autosave")) {
        const bool settings_were_modified = std::exchange(settings_modified_, false);
        undo_->setClean();
        if (settings_were_modified && !isModified()) emit modifiedChanged(false);
        file_path_ = path;
        emit filePathChanged(path);
    }
    return true;
}

Result<Project> ProjectDocument::load(const QString& path, const io::PresetLocations* locations) {
    return project::loadProject(path.toStdString(), locations);
}

Project ProjectDocument::defaultProject(const io::PresetLocations& locations) {
    Project project;
    if (auto soil = io::resolveSoil(locations, "sandy-loam")) project.soil = *soil;
    if (auto wheel = io::resolveWheel(locations, "A")) project.wheel = *wheel;
    return project;
}

}  // namespace terra::ui
