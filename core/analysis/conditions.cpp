#include "core/analysis/conditions.h"

#include <array>

#include "core/analysis/sweep.h"

namespace terra::analysis {

std::vector<double> OperatingConditions::slips() const {
    return linspace(0.0, slip_max, slip_count);
}

const FieldInfo& slipAnglesField() {
    static const FieldInfo field = [] {
        FieldInfo f = contact::slipAngleField();
        f.key = "slip_angles_deg";
        f.label = "slip angles";
        f.description = "Slip angles β of the force sweeps (Eq. 2.2), in degrees, one curve each.";
        return f;
    }();
    return field;
}

const FieldInfo& slipMaxField() {
    static const FieldInfo field{"slip_max",
                                 "-",
                                 "s_max",
                                 "largest slip",
                                 "Largest slip of the force sweeps; the grid runs from 0 to it "
                                 "in slip_count points. Dimensionless.",
                                 {0.0, 1.0, true, false}};
    return field;
}

const FieldInfo& slipCountField() {
    static const FieldInfo field{"slip_count",
                                 "-",
                                 "N_s",
                                 "slip points",
                                 "Number of slips of the force sweeps, 0 … slip_max.",
                                 {2.0, 10000.0}};
    return field;
}

std::span<const FieldInfo* const> conditionsFields() {
    static const std::array<const FieldInfo*, 4> fields{&contact::loadField(), &slipAnglesField(),
                                                        &slipCountField(), &slipMaxField()};
    return fields;
}

void readConditions(io::ObjectReader& r, OperatingConditions& out) {
    const FieldInfo& load = contact::loadField();
    r.number(load.key, out.load_n, load.range, load.displayUnit());
    const FieldInfo& beta = slipAnglesField();
    r.numbers(beta.key, out.slip_angles_deg, beta.range, beta.displayUnit(), 1, 1000);
    const FieldInfo& count = slipCountField();
    r.integer(count.key, out.slip_count, static_cast<int>(count.range.low),
              static_cast<int>(count.range.high));
    const FieldInfo& slip_max = slipMaxField();
    r.number(slip_max.key, out.slip_max, slip_max.range);
    r.choice<bool>("model", out.quadratic, {{"full", false}, {"quadratic", true}});
}

nlohmann::json toJson(const OperatingConditions& c) {
    return {{"load_N", c.load_n},
            {"slip_angles_deg", c.slip_angles_deg},
            {"slip_count", c.slip_count},
            {"slip_max", c.slip_max},
            {"model", c.quadratic ? "quadratic" : "full"}};
}

std::vector<Issue> validate(const OperatingConditions& c, const std::string& prefix) {
    std::vector<Issue> issues;
    const FieldInfo& load = contact::loadField();
    checkRange(issues, prefix + load.key, c.load_n, load.range, load.displayUnit());
    const FieldInfo& beta = slipAnglesField();
    if (c.slip_angles_deg.empty()) issues.push_back({prefix + beta.key, "no slip angles"});
    for (std::size_t i = 0; i < c.slip_angles_deg.size(); ++i) {
        checkRange(issues, prefix + "slip_angles_deg[" + std::to_string(i) + "]",
                   c.slip_angles_deg[i], beta.range, beta.displayUnit());
    }
    checkRange(issues, prefix + slipCountField().key, c.slip_count, slipCountField().range);
    checkRange(issues, prefix + slipMaxField().key, c.slip_max, slipMaxField().range);
    return issues;
}

}  // namespace terra::analysis
