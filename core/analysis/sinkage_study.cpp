#include "core/analysis/sinkage_study.h"

#include <cmath>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/contact/sinkage.h"
#include "core/io/declared_json.h"

namespace terra::analysis {

void readSinkageSettings(io::ObjectReader& r, SinkageSettings& out) { io::readFields(r, out); }

nlohmann::json toJson(const SinkageSettings& settings) { return io::fieldsToJson(settings); }

SinkageStudy computeSinkage(const Inputs& in, const SinkageSettings& s, const Control& control) {
    const std::vector<double> loads =
        s.loads_n.empty() ? std::vector<double>{in.conditions.load_n} : s.loads_n;
    // The reader's checks, in its words, for settings built in code; the conditions' load when
    // the settings give none.
    std::vector<Issue> issues = io::fieldIssues(s);
    if (s.loads_n.empty()) {
        const FieldInfo& load = contact::loadField();
        checkRange(issues, load.key, in.conditions.load_n, load.range, load.displayUnit());
    }
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    const auto p = in.contact();
    SinkageStudy out;
    out.table.columns = {"load_N",
                         "bekker_sinkage_m",
                         "static_sinkage_m",
                         "static_angle_deg",
                         "static_front_half_sinkage_m",
                         "entry_angle_deg",
                         "sinkage_m"};
    for (double w : loads) {
        if (control.cancelled()) {
            out.cancelled = true;
            break;
        }
        const double bekker = contact::bekkerStaticSinkage(p, w);
        const auto exact = contact::solveStaticSinkage(p, w, contact::StaticContact::kSymmetric);
        const auto front = contact::solveStaticSinkage(p, w, contact::StaticContact::kFrontHalf);
        contact::EntryAngleProblem problem;
        problem.load_n = w;
        problem.slip = s.slip;
        problem.slip_angle_rad = units::degToRad(s.slip_angle_deg);
        problem.exit = s.model.exit;
        problem.max_stress_angle_rad = s.model.max_stress_angle_rad;
        problem.model = in.conditions.model();
        const auto dynamic = contact::solveEntryAngle(p, problem);
        const double nan = std::nan("");
        out.table.rows.push_back({w, bekker, exact.ok() ? exact.sinkage_m : nan,
                                  exact.ok() ? units::radToDeg(exact.entry_angle_rad) : nan,
                                  front.ok() ? front.sinkage_m : nan,
                                  dynamic.ok() ? units::radToDeg(dynamic.entry_angle_rad) : nan,
                                  dynamic.ok() ? dynamic.sinkage_m : nan});
        const std::pair<const char*, const contact::SinkageSolution*> solves[] = {
            {"static (Eq. 2.7)", &exact},
            {"static front half", &front},
            {"dynamic entry angle", &dynamic}};
        for (const auto& [what, solution] : solves) {
            if (!solution->ok()) {
                out.notes.push_back("W = " + formatNumber(w) + " N, " + what + ": " +
                                    solution->message);
            }
        }
        if (bekker > p.radius_m / 3.0) {
            out.notes.push_back("W = " + formatNumber(w) +
                                " N: Bekker's formula is outside its validity (h > r/3)");
        }
    }
    return out;
}

Outcome sinkageOutcome(SinkageStudy study) {
    Outcome out;
    if (study.cancelled) out.status = Outcome::Status::kCancelled;
    out.tables.push_back({"sinkage", "", study.table});
    out.notes = study.notes;
    out.result = std::move(study);
    return out;
}

AnalysisType sinkageType() {
    return makeAnalysisType<SinkageSettings>(
        "sinkage",
        "static sinkage (Bekker Eq. 2.8, Eq. 2.7) and the dynamic entry angle against load",
        {"sinkage"}, {},
        [](io::ObjectReader& r, const ReadContext&, SinkageSettings& s) {
            readSinkageSettings(r, s);
        },
        [](const Inputs& in, const SinkageSettings& s, const Control& c) {
            return computeSinkage(in, s, c);
        },
        sinkageOutcome);
}

}  // namespace terra::analysis
