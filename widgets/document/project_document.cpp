#include "widgets/document/project_document.h"

#include <QDir>
#include <QFileInfo>
#include <QSaveFile>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "core/common/range.h"

namespace terra::ui {
namespace {

/// Undo and redo both call one setter of the document with the value to install.
template <typename T>
class SetValueCommand : public QUndoCommand {
public:
    SetValueCommand(const QString& text, int merge_id, int gesture, T before, T after,
                    std::function<void(const T&)> apply)
        : QUndoCommand(text),
          merge_id_(merge_id),
          gesture_(gesture),
          before_(std::move(before)),
          after_(std::move(after)),
          apply_(std::move(apply)) {}
    void undo() override { apply_(before_); }
    void redo() override { apply_(after_); }
    int id() const override { return merge_id_; }
    bool mergeWith(const QUndoCommand* other) override {
        // Same id implies same field and type: a drag of one slider becomes one undo step. A new
        // gesture (endMerge(): slider released, typing finished) starts a step of its own.
        const auto* next = static_cast<const SetValueCommand*>(other);
        if (next->gesture_ != gesture_) return false;
        after_ = next->after_;
        setText(next->text());  // the label names the value the step ends on
        return true;
    }

private:
    int merge_id_;
    int gesture_;
    T before_, after_;
    std::function<void(const T&)> apply_;
};

// Merge ids: one per field; -1 (no merging) for whole-object replacements.
constexpr int kSoilFieldIdBase = 100, kSoilNameId = 150;
constexpr int kWheelFieldIdBase = 200, kLoadId = 300, kSlipAnglesId = 301, kModelId = 302;

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
        case Part::kScenarios:
            emit scenariosChanged();
            break;
        case Part::kExperiment:
            emit experimentChanged();
            break;
    }
    emit changed();
}

template <typename T>
bool ProjectDocument::pushField(const QString& text, int merge_id, Part part, T* field,
                                const T& value) {
    if (*field == value) return true;
    undo_->push(new SetValueCommand<T>(text, merge_id, gesture_, *field, value,
                                       [this, field, part](const T& v) {
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

std::string ProjectDocument::editedSoilName(const Project& project) {
    // Leaving a preset: the soil is no longer that preset, and says so wherever its name goes.
    if (project.soil_preset.empty()) return project.soil.name;
    const std::string suffix = " (edited)";
    const std::string& name = project.soil.name.empty() ? project.soil_preset : project.soil.name;
    return name.ends_with(suffix) ? name : name + suffix;
}

bool ProjectDocument::pushSoil(const QString& text, int merge_id, soil::SoilParameters soil,
                               const std::string& preset) {
    using Pair = std::pair<soil::SoilParameters, std::string>;
    const Pair before{project_.soil, project_.soil_preset}, after{std::move(soil), preset};
    if (io::toJson(before.first) == io::toJson(after.first) && before.second == after.second)
        return true;
    undo_->push(
        new SetValueCommand<Pair>(text, merge_id, gesture_, before, after, [this](const Pair& v) {
            project_.soil = v.first;
            project_.soil_preset = v.second;
            notify(Part::kSoil);
        }));
    return true;
}

bool ProjectDocument::setSoilValue(const std::string& key, double user_value) {
    const auto fields = soil::soilFields();
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const soil::SoilField& field = fields[i];
        if (key != field.key) continue;
        // j_max is optional: +inf is "no limit" (the range itself excludes it).
        const bool no_limit =
            key == "jmax_m" && user_value == std::numeric_limits<double>::infinity();
        if (!no_limit && !field.range.contains(user_value)) return false;
        if (roundSignificant(soil::userValue(project_.soil, field)) == roundSignificant(user_value))
            return true;
        soil::SoilParameters candidate = project_.soil;
        soil::setUserValue(candidate, field, user_value);
        if (!soil::validate(candidate).empty()) return false;
        candidate.name = editedSoilName(project_);
        const QString value =
            no_limit
                ? QString("no limit")
                : QString("%1 %2").arg(user_value).arg(QString::fromStdString(field.displayUnit()));
        return pushSoil(
            QString("Set %1 = %2").arg(QString::fromUtf8(field.symbol), value.trimmed()),
            kSoilFieldIdBase + static_cast<int>(i), std::move(candidate), "");
    }
    return false;
}

bool ProjectDocument::setSoilName(const std::string& name) {
    if (name.empty() || name == project_.soil.name) return !name.empty();
    soil::SoilParameters candidate = project_.soil;
    candidate.name = name;
    // A name of one's own is a custom soil, even with a preset's values.
    return pushSoil(QString("Rename soil to %1").arg(QString::fromStdString(name)), kSoilNameId,
                    std::move(candidate), "");
}

std::string ProjectDocument::wheelValueProblem(const std::string& key, double value) const {
    const wheel::WheelField* field = wheel::findWheelField(key);
    if (!field) return key + ": not a wheel field";
    wheel::WheelParameters candidate = project_.wheel;
    field->setUserValue(candidate, value);
    const std::vector<Issue> issues = wheel::validate(candidate);
    return issues.empty() ? std::string() : formatIssues(issues);
}

bool ProjectDocument::setWheelValue(const std::string& key, double value) {
    const std::span<const wheel::WheelField> fields = wheel::wheelFields();
    const wheel::WheelField* field = wheel::findWheelField(key);
    // wheel::validate checks the field's range and the cross-field rules (grousers below r).
    if (!field || !wheelValueProblem(key, value).empty()) return false;
    wheel::WheelParameters candidate = project_.wheel;
    field->setUserValue(candidate, value);
    if (candidate.*field->member == project_.wheel.*field->member) return true;
    if (!project_.wheel_preset.empty()) {
        const std::string suffix = " (edited)";
        const std::string& name = candidate.name.empty() ? project_.wheel_preset : candidate.name;
        candidate.name = name.ends_with(suffix) ? name : name + suffix;
    }
    const int merge_id = kWheelFieldIdBase + static_cast<int>(field - fields.data());
    return pushWheel(
        QString("Set wheel %1 = %2%3")
            .arg(QString::fromUtf8(field->symbol))
            .arg(value)
            .arg(field->displayUnit().empty() ? QString()
                                              : " " + QString::fromStdString(field->displayUnit())),
        merge_id, std::move(candidate), "");
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

bool ProjectDocument::setSoil(const soil::SoilParameters& soil, const std::string& preset,
                              const QString& text) {
    if (!soil::validate(soil).empty()) return false;
    return pushSoil(
        text.isEmpty() ? QString("Soil preset %1").arg(QString::fromStdString(preset)) : text, -1,
        soil, preset);
}

bool ProjectDocument::setWheel(const wheel::WheelParameters& wheel, const std::string& preset) {
    if (!wheel::validate(wheel).empty()) return false;
    return pushWheel(QString("Wheel preset %1").arg(QString::fromStdString(preset)), -1, wheel,
                     preset);
}

bool ProjectDocument::pushWheel(const QString& text, int merge_id, wheel::WheelParameters wheel,
                                const std::string& preset) {
    using Pair = std::pair<wheel::WheelParameters, std::string>;
    const Pair before{project_.wheel, project_.wheel_preset}, after{std::move(wheel), preset};
    if (io::toJson(before.first) == io::toJson(after.first) && before.second == after.second)
        return true;
    undo_->push(
        new SetValueCommand<Pair>(text, merge_id, gesture_, before, after, [this](const Pair& v) {
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

bool ProjectDocument::addScenario(const std::string& path) {
    std::vector<std::string> scenarios = project_.scenarios;
    if (std::find(scenarios.begin(), scenarios.end(), path) != scenarios.end()) return true;
    scenarios.push_back(path);
    return pushField("Add scenario " + QFileInfo(QString::fromStdString(path)).fileName(), -1,
                     Part::kScenarios, &project_.scenarios, scenarios);
}

ProjectDocument::ExperimentState ProjectDocument::readExperiment(const std::string& path) const {
    ExperimentState state{path, nullptr, {}};
    if (path.empty()) return state;
    QString resolved = QString::fromStdString(path);
    // A relative path is relative to the .terra file (load() resolves those of the file).
    if (QFileInfo(resolved).isRelative() && !file_path_.isEmpty())
        resolved = QFileInfo(file_path_).dir().filePath(resolved);
    Result<io::Experiment> read = io::readExperiment(resolved.toStdString());
    if (read) {
        state.data = std::make_shared<const io::Experiment>(std::move(read.value()));
    } else {
        state.error = read.message();
    }
    return state;
}

bool ProjectDocument::setExperiment(const QString& path, QString* error) {
    const std::string absolute =
        path.isEmpty() ? std::string() : QFileInfo(path).absoluteFilePath().toStdString();
    if (absolute == project_.experiment) return true;
    ExperimentState after = readExperiment(absolute);
    if (!after.error.empty()) {
        if (error) *error = QString::fromStdString(after.error);
        return false;
    }
    const QString text = absolute.empty()
                             ? QString("Remove experiment")
                             : QString("Load experiment %1").arg(QFileInfo(path).fileName());
    undo_->push(new SetValueCommand<ExperimentState>(
        text, -1, gesture_, experiment_, std::move(after), [this](const ExperimentState& v) {
            project_.experiment = v.path;
            experiment_ = v;
            notify(Part::kExperiment);
        }));
    return true;
}

void ProjectDocument::setPanelSettings(const std::string& panel, const nlohmann::json& settings) {
    if (project_.panels.contains(panel) && project_.panels[panel] == settings) return;
    project_.panels[panel] = settings;
    // Not undoable, but saved with the project (an edited scenario lives here): unsaved, it must
    // make the close ask and the autosave run like any other change. Settings stored again as they
    // were saved (Run stores the scenario chosen; a control set back) are no change.
    const bool was_modified = isModified();
    settings_modified_ = project_.panels != saved_panels_;
    if (isModified() != was_modified) emit modifiedChanged(isModified());
    emit panelSettingsChanged();
}

void ProjectDocument::reset(const Project& project, const QString& file_path) {
    project_ = project;
    settings_modified_ = false;
    saved_panels_ = project_.panels;
    undo_->clear();
    undo_->setClean();
    file_path_ = file_path;
    // A test that cannot be read any more (moved, edited) keeps its reference and says why
    // (experimentError()); the project opens all the same.
    experiment_ = readExperiment(project_.experiment);
    emit filePathChanged(file_path_);
    for (Part part : {Part::kSoil, Part::kWheel, Part::kConditions, Part::kDataSets,
                      Part::kScenarios, Part::kExperiment})
        notify(part);
    emit modifiedChanged(false);
}

void ProjectDocument::markUnmodified() {
    const bool was_modified = isModified();
    settings_modified_ = false;
    saved_panels_ = project_.panels;
    undo_->setClean();
    if (was_modified) emit modifiedChanged(false);
}

bool ProjectDocument::save(const QString& path, QString* error) {
    QSaveFile file(path);  // a temporary file, renamed over the old one on commit()
    // Files inside the project's folder are written relative to it: the folder can be moved.
    const std::string text =
        toJson(project::withRelativePaths(
                   project_, QFileInfo(path).absoluteDir().absolutePath().toStdString()))
            .dump(2) +
        "\n";
    if (!file.open(QIODevice::WriteOnly) ||
        file.write(text.data(), static_cast<qint64>(text.size())) !=
            static_cast<qint64>(text.size()) ||
        !file.commit()) {
        if (error) *error = QString("cannot save %1: %2").arg(path, file.errorString());
        return false;
    }
    if (!path.endsWith(".autosave")) {
        const bool settings_were_modified = std::exchange(settings_modified_, false);
        saved_panels_ = project_.panels;
        undo_->setClean();
        if (settings_were_modified && !isModified()) emit modifiedChanged(false);
        file_path_ = path;
        emit filePathChanged(path);
    }
    return true;
}

Result<Project> ProjectDocument::load(const QString& path, const io::PresetLocations* locations) {
    Result<Project> project = project::loadProject(path.toStdString(), locations);
    if (!project) return project;
    return project::withAbsolutePaths(*project,
                                      QFileInfo(path).absoluteDir().absolutePath().toStdString());
}

Project ProjectDocument::defaultProject(const io::PresetLocations& locations) {
    Project project;
    if (auto soil = io::resolveSoil(locations, "sandy-loam")) project.soil = *soil;
    if (auto wheel = io::resolveWheel(locations, "A")) project.wheel = *wheel;
    return project;
}

}  // namespace terra::ui
