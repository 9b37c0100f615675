#include "core/analysis/analysis.h"

#include <stdexcept>

#include "core/common/units.h"
#include "core/contact/operating_fields.h"

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

void readModelChoices(io::ObjectReader& r, ModelChoices& out) {
    const FieldInfo& exit = contact::exitAngleField();
    const FieldInfo& rut = contact::rutRatioField();
    if (r.has(exit.key) && r.has(rut.key)) {
        r.report(rut.key, std::string("give ") + exit.key + " or " + rut.key + ", not both");
    }
    // Angles converted as the command line always has (units::degToRad), bit for bit.
    const FieldInfo& theta_m = contact::maxStressAngleField();
    double value = 0.0;
    if (r.number(exit.key, value, exit.range, exit.displayUnit())) {
        out.exit = {contact::ExitCondition::Kind::kAngle, units::degToRad(value)};
    }
    if (r.number(rut.key, value, rut.range))
        out.exit = {contact::ExitCondition::Kind::kRutRatio, value};
    if (r.number(theta_m.key, value, theta_m.range, theta_m.displayUnit())) {
        out.max_stress_angle_rad = units::degToRad(value);
    }
    r.choice<contact::BulldozingModel>("bulldozing", out.bulldozing,
                                       {{"bekker", contact::BulldozingModel::kBekker},
                                        {"hegedus", contact::BulldozingModel::kHegedus}});
}

void writeModelChoices(const ModelChoices& choices, nlohmann::json& out) {
    if (choices.exit.kind == contact::ExitCondition::Kind::kRutRatio) {
        out[contact::rutRatioField().key] = choices.exit.value;
    } else if (choices.exit.value != 0.0) {
        out[contact::exitAngleField().key] = roundSignificant(units::radToDeg(choices.exit.value));
    }
    if (choices.max_stress_angle_rad) {
        out[contact::maxStressAngleField().key] =
            roundSignificant(units::radToDeg(*choices.max_stress_angle_rad));
    }
    if (choices.bulldozing == contact::BulldozingModel::kHegedus) out["bulldozing"] = "hegedus";
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
