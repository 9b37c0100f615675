#include "core/analysis/forces.h"

#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"

namespace terra::analysis {

void readForcesSettings(io::ObjectReader& r, ForcesSettings& out) { io::readFields(r, out); }

nlohmann::json toJson(const ForcesSettings& settings) { return io::fieldsToJson(settings); }

SweepSpec forcesSpec(const Inputs& in, const ForcesSettings& settings, const Control& control) {
    SweepSpec spec;
    spec.slips = settings.slips.empty() ? in.conditions.slips() : settings.slips;
    for (double beta : in.conditions.slip_angles_deg)
        spec.slip_angles_rad.push_back(units::degToRad(beta));
    if (settings.entry_angle_deg) {
        spec.load_n.reset();
        spec.entry_angle_rad = units::degToRad(*settings.entry_angle_deg);
    } else {
        spec.load_n = in.conditions.load_n;
    }
    spec.exit = settings.model.exit;
    spec.max_stress_angle_rad = settings.model.max_stress_angle_rad;
    spec.bulldozing = settings.model.bulldozing;
    spec.model = in.conditions.model();
    spec.threads = settings.threads;
    spec.cancel = control.cancel;
    spec.progress = control.progress;
    return spec;
}

ForcesResult computeForceSweep(const Inputs& in, const ForcesSettings& settings,
                               const Control& control) {
    // The reader's checks, in its words, for settings built in code (a panel's, a test's).
    if (const std::vector<Issue> issues = io::fieldIssues(settings); !issues.empty())
        throw std::invalid_argument(formatIssues(issues));
    return sweepSlip(in.contact(), forcesSpec(in, settings, control));
}

Outcome forcesOutcome(ForcesResult result) {
    Outcome out;
    out.status = result.cancelled ? Outcome::Status::kCancelled : Outcome::Status::kCompleted;
    out.tables.push_back({"sweep", "", result.table});
    out.notes = result.warnings;
    out.result = std::move(result);
    return out;
}

AnalysisType forcesType() {
    std::vector<FigureSpec> figures;
    for (const char* column : {"Fx_N", "Fs_N", "Fz_N", "My_Nm", "Mz_Nm", "entry_angle_deg"})
        figures.push_back({column, std::string("-") + column});
    return makeAnalysisType<ForcesSettings>(
        "forces", "forces and moments against slip for each slip angle (Figs. 2.18-2.26)",
        {"sweep"}, std::move(figures),
        [](io::ObjectReader& r, const ReadContext&, ForcesSettings& s) {
            readForcesSettings(r, s);
        },
        [](const Inputs& in, const ForcesSettings& s, const Control& c) {
            return computeForceSweep(in, s, c);
        },
        forcesOutcome);
}

}  // namespace terra::analysis
