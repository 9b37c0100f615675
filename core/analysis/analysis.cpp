#include "core/analysis/analysis.h"

#include <stdexcept>

#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"

namespace terra::analysis {

contact::ContactParameters<double> Inputs::contact() const {
    return contact::makeContactParameters(soil, wheel);
}

std::vector<Issue> validate(const Inputs& inputs) {
    std::vector<Issue> issues = soil::validate(inputs.soil, "soil.");
    for (Issue& issue : wheel::validate(inputs.wheel, "wheel.")) issues.push_back(issue);
    for (Issue& issue : validate(inputs.conditions)) issues.push_back(issue);
    if (issues.empty()) {
        try {
            inputs.contact();
        } catch (const std::invalid_argument& e) {
            issues.push_back({"soil", e.what()});
        }
    }
    return issues;
}

void exitConditionRule(io::ObjectReader& r) {
    const FieldInfo& exit = contact::exitAngleField();
    const FieldInfo& rut = contact::rutRatioField();
    if (r.has(exit.key) && r.has(rut.key)) {
        r.report(rut.key, std::string("give ") + exit.key + " or " + rut.key + ", not both");
    }
}

void readExitAngle(io::ObjectReader& r, const char* key, contact::ExitCondition& out) {
    exitConditionRule(r);
    const FieldInfo& exit = contact::exitAngleField();
    double value = 0.0;
    if (r.number(key, value, exit.range, exit.displayUnit()))
        out = {contact::ExitCondition::Kind::kAngle, units::degToRad(value)};
}

nlohmann::json exitAngleJson(const contact::ExitCondition& exit) {
    if (exit.kind != contact::ExitCondition::Kind::kAngle || exit.value == 0.0) return nullptr;
    return roundSignificant(units::radToDeg(exit.value));
}

void readRutRatio(io::ObjectReader& r, const char* key, contact::ExitCondition& out) {
    double value = 0.0;
    if (r.number(key, value, contact::rutRatioField().range))
        out = {contact::ExitCondition::Kind::kRutRatio, value};
}

nlohmann::json rutRatioJson(const contact::ExitCondition& exit) {
    if (exit.kind != contact::ExitCondition::Kind::kRutRatio) return nullptr;
    return exit.value;
}

void readMaxStressAngle(io::ObjectReader& r, const char* key, std::optional<double>& out_rad) {
    const FieldInfo& theta_m = contact::maxStressAngleField();
    double value = 0.0;
    if (r.number(key, value, theta_m.range, theta_m.displayUnit()))
        out_rad = units::degToRad(value);
}

nlohmann::json maxStressAngleJson(const std::optional<double>& rad) {
    if (!rad) return nullptr;
    return roundSignificant(units::radToDeg(*rad));
}

void readBulldozing(io::ObjectReader& r, const char* key, contact::BulldozingModel& out) {
    r.choice<contact::BulldozingModel>(key, out,
                                       {{"bekker", contact::BulldozingModel::kBekker},
                                        {"hegedus", contact::BulldozingModel::kHegedus}});
}

nlohmann::json bulldozingJson(const contact::BulldozingModel& model) {
    if (model != contact::BulldozingModel::kHegedus) return nullptr;
    return "hegedus";
}

void readModelChoices(io::ObjectReader& r, ModelChoices& out) { io::readFields(r, out); }

void writeModelChoices(const ModelChoices& choices, nlohmann::json& out) {
    out.update(io::fieldsToJson(choices));
}

const char* statusName(Outcome::Status status) {
    switch (status) {
        case Outcome::Status::kCompleted:
            return "completed";
        case Outcome::Status::kCancelled:
            return "cancelled";
        case Outcome::Status::kFailed:
            return "failed";
        case Outcome::Status::kInvalidInput:
            return "invalid input";
    }
    return "?";
}

const Table* Outcome::table(std::string_view name) const {
    if (tables.empty()) return nullptr;
    if (name.empty()) return &tables.front().table;
    for (const NamedTable& t : tables) {
        if (t.name == name) return &t.table;
    }
    return nullptr;
}

}  // namespace terra::analysis
