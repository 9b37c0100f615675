#pragma once
/// @file rover.h
/// A rover scenario run (thesis chapter 3, docs/dynamics.md): the 4WD/4WS robot driven through a
/// scenario on its soils, with its time series, summary and optional streaming identification.
/// The studio's rover panel, `terrastudio simulate` and a script's "rover" analysis. The
/// scenario brings its own robot and soils: a project's soil, wheel and conditions do not apply.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/common/declared_fields.h"
#include "core/io/declared_optional.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario.h"

namespace terra::analysis {

struct AnalysisType;
struct ReadContext;

struct RoverSettings {
    std::string scenario = "straight";  ///< a scenario preset (resources/scenarios) or a file
    std::optional<scenario::Scenario>
        loaded;                         ///< that scenario, resolved (by the reader or caller)
    std::optional<double> duration_s;   ///< overrides the scenario's duration [s]
    std::optional<double> time_step_s;  ///< overrides its time step [s]
    std::optional<contact::ContactModel> model;  ///< overrides its contact model
    /// Overrides its controller's type (docs/traction.md §5), e.g. to compare controllers on one
    /// scenario; the controller's other settings stay the scenario's.
    std::optional<scenario::ControllerType> controller;
    std::optional<double> slip;  ///< overrides the controller's fixed set-point [-]
    /// The robot and its soils changed for one run of a study of many missions (docs/field.md,
    /// "Mission studies"): the chassis mass [kg], the wheel of all four corners, and soils by
    /// "base", a field's class code ("2") or a patch terrain's patch number ("1", from 1). A
    /// soil given without a profile keeps the profile of the soil it replaces.
    std::optional<double> chassis_mass_kg;
    std::optional<wheel::WheelParameters> wheel;
    std::map<std::string, soil::SoilParameters> soils;
    /// Overrides the controller's traction-limited mode (docs/traction.md §5).
    std::optional<bool> traction_limited;
    /// Override the optimal controller's robust set-point, its quantile, soils drawn, the
    /// posterior's method and the streaming soil estimator (docs/traction.md §8).
    std::optional<scenario::RobustSlip> robust;
    std::optional<double> quantile;
    std::optional<int> posterior_samples;
    std::optional<scenario::PosteriorMethod> posterior_method;
    std::optional<scenario::SoilIdentifier> identifier;

    /// Its file keys, one line each (core/common/declared_fields.h; the overrides absent unless
    /// given, core/io/declared_optional.h): the reader, toJson, the command line's flags and
    /// runRover's checks are made from them. The resolved scenario (`loaded`) is not a file key.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "wheel" as a wheel object; a preset or file name is left to readRoverSettings (which finds it
/// through the context's presets). Problems are reported at `key`.
void readWheelOverride(io::ObjectReader& r, const char* key,
                       std::optional<wheel::WheelParameters>& out);
/// "soils" ({"base" | CODE | PATCH: a soil object}); names of presets or files are left to
/// readRoverSettings.
void readSoilOverrides(io::ObjectReader& r, const char* key,
                       std::map<std::string, soil::SoilParameters>& out);
/// Their JSON: the wheel's and each soil's file object; null when empty.
nlohmann::json wheelOverrideJson(const std::optional<wheel::WheelParameters>& wheel);
nlohmann::json soilOverridesJson(const std::map<std::string, soil::SoilParameters>& soils);

template <typename Visitor>
void RoverSettings::visitFields(Visitor& v) {
    using scenario::ControllerType;
    using scenario::PosteriorMethod;
    using scenario::RobustSlip;
    using scenario::SoilIdentifier;
    v(fields::text("scenario", scenario,
                   "a scenario preset or file (required; relative to the script, resolved at "
                   "once)"));
    v(fields::number("duration_s", duration_s, scenario::kDurationRange, "s",
                     "overrides the scenario's duration"));
    v(fields::number("time_step_s", time_step_s, scenario::kTimeStepRange, "s",
                     "overrides the scenario's time step"));
    v(io::optionalChoice<ControllerType>("controller", controller,
                                         {{"constant-speed", ControllerType::kConstantSpeed},
                                          {"fixed-slip", ControllerType::kFixedSlip},
                                          {"optimal", ControllerType::kOptimal},
                                          {"oracle", ControllerType::kOracle}},
                                         "constant-speed, fixed-slip, optimal, oracle",
                                         "overrides the controller's type"));
    v(fields::number("slip", slip, scenario::kControllerRanges.slip, "",
                     "overrides the controller's fixed slip set-point"));
    v(io::optionalFlag("traction_limited", traction_limited,
                       "overrides the slip controllers' traction-limited mode"));
    v(io::optionalChoice<RobustSlip>("robust", robust,
                                     {{"none", RobustSlip::kNone},
                                      {"expected", RobustSlip::kExpected},
                                      {"quantile", RobustSlip::kQuantile}},
                                     "none, expected, quantile",
                                     "overrides the optimal controller's robust set-point"));
    v(fields::field(scenario::robustQuantileField(), quantile));
    v(io::optionalInteger("posterior_samples", posterior_samples, scenario::kMinPosteriorSamples,
                          scenario::kMaxPosteriorSamples, "[10, 100000]",
                          "overrides the soils drawn from the posterior"));
    v(io::optionalChoice<PosteriorMethod>(
        "posterior_method", posterior_method,
        {{"sigma-points", PosteriorMethod::kSigmaPoints}, {"samples", PosteriorMethod::kSamples}},
        "sigma-points, samples", "overrides how a robust set-point carries the posterior"));
    v(io::optionalChoice<SoilIdentifier>(
        "identifier", identifier,
        {{"decoupled", SoilIdentifier::kDecoupled}, {"full", SoilIdentifier::kFull}},
        "decoupled, full", "overrides the optimal controller's soil estimator"));
    v(fields::field(*findField(dynamics::robotFields(), "chassis_mass_kg"), chassis_mass_kg));
    v(fields::custom("wheel", wheel, "preset, path or object", "a wheel preset, file or object",
                     "the wheel of all four corners", readWheelOverride, wheelOverrideJson));
    v(fields::custom("soils", soils, "object", "{\"base\" | class code | patch number: soil}",
                     "soils replaced, each a preset, file or soil object", readSoilOverrides,
                     soilOverridesJson));
    v(io::optionalChoice<contact::ContactModel>(
        "model", model,
        {{"full", contact::ContactModel::kFull}, {"quadratic", contact::ContactModel::kQuadratic}},
        "full, quadratic", "overrides the contact model"));
}

/// The keys of RoverSettings::visitFields, read strictly (io::readFields), then what a field list
/// cannot say: "scenario" is required and resolved at once (relative files against the context's
/// directory), a wheel or soils named by preset or file are found through the context, and the
/// overrides are checked against the scenario they change (a duration below one step, a step the
/// robot cannot take, a class the field does not have, a wheel too wide for the track).
void readRoverSettings(io::ObjectReader& r, const ReadContext& context, RoverSettings& out);
/// The settings' file keys (io::fieldsToJson): the scenario's name, the overrides given, the
/// wheel and soils as objects; what readRoverSettings reads back.
nlohmann::json toJson(const RoverSettings& settings);

/// The soils a run's "soils" override can replace, by its keys: "base", then a field's class
/// codes ("1", "2", …) or a patch terrain's patch numbers ("1", …), each with its soil as the
/// scenario has it (a study draws its variations around these).
std::vector<std::pair<std::string, soil::SoilParameters>> overridableSoils(
    const scenario::Scenario& scenario);

/// The scenario with the overrides applied; throws std::invalid_argument when it is not
/// resolved or an override is out of range (the reader's checks, in its words: io::fieldIssues).
scenario::Scenario roverScenario(const RoverSettings& settings);

/// The figures of a run (rover_figures.h draws them), in the panel's order, and the top view.
const std::vector<std::string>& roverFigureKeys();

struct RoverResult {
    scenario::Scenario scenario;  ///< as run (the top view draws its robot and soils)
    scenario::RunResult run;
};

/// s* by computeTraction (docs/traction.md §1) with the quadratic model on a 30-slip curve: the
/// optimal and oracle controllers' planner.
scenario::SlipPlanner tractionPlanner();

/// Runs it (progress and cancel from `control`; the slip planner is tractionPlanner()). Throws
/// std::invalid_argument when the robot cannot be set up (scenario::runScenario).
RoverResult runRover(const RoverSettings& settings, const Control& control = {});

/// A run's summary as a one-row table for expectations: every number of the summary JSON
/// (nested objects flattened: mean_slip_FL …), yaw_deg, and the largest |y| and |yaw| over the
/// run (max_abs_y_m, max_abs_yaw_deg: a straight line stays on its line all along).
Table roverSummaryTable(const RoverResult& result);

/// The run for a person, as `terrastudio simulate` prints it: a heading with the scenario, the
/// simulated time and the steps; the status when not completed; the final pose (yaw in deg), the
/// distance, each wheel's mean slip, the motor energy (and into the soil); a field run's cells
/// touched, deepest rut and largest compaction risk at its depth; a mission's time, progress and
/// path error; the energy balance's warning. Each number's `json` points at it in
/// scenario::toJson(run, scenario).
Summary roverSummary(const scenario::RunResult& run, const scenario::Scenario& scenario);

/// Tables "summary" (main, not written as CSV), "timeseries", "streaming" (when the scenario has
/// the hook); the document "-summary.json"; notes: the status, warnings and the final pose. A
/// diverged run is a failure, a cancelled one cancelled; both keep their partial tables.
Outcome roverOutcome(RoverResult result);

/// One controller's run of a comparison (docs/traction.md §6).
struct ControllerRun {
    std::string controller;  ///< controllerName()
    scenario::RunResult run;
};

/// The comparison table (comparison.json, the studio's table): per run "controller", "status",
/// "distance_m", "energy_per_m_J", "mean_efficiency", "energy_per_drawbar_work" (drive work over
/// the implement's work), "mean_drawbar_N" (the implement's work over the distance),
/// "drawbar_vs_oracle" (over the oracle run's; null without one), "mean_slip" ({FL, FR, RL, RR}
/// as the summary's), "slip_tracking_rms",
/// "settling_time_s", "rut_depth_m"; null where a figure is not defined.
nlohmann::json controllerComparison(const std::vector<ControllerRun>& runs);

/// Runs `settings`'s scenario under every controller in turn (scenario::controllerNames()), each
/// an equal share of `control`'s progress. `on_run`, when set, sees each finished run (with its
/// scenario) before the next starts and may move from it; the CLI writes its files there, the
/// studio keeps the run it shows. A cancelled run ends the comparison: the runs so far are
/// returned, the cancelled one last. Throws std::invalid_argument as runRover does; an exception
/// from `on_run` ends the comparison and propagates (the runs so far are dropped).
std::vector<ControllerRun> compareControllers(
    const RoverSettings& settings, const Control& control = {},
    const std::function<void(const std::string& controller, RoverResult& result)>& on_run = {});

AnalysisType roverType();

}  // namespace terra::analysis
