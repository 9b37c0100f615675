#include "app/cli/cli_support.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>

#include "core/analysis/sweep.h"
#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace terra::app {

void ModelOptions::addTo(CLI::App& command, bool with_geometry) {
    command.add_option("--soil", soil, "Soil preset name or JSON file")->capture_default_str();
    command.add_option("--wheel", wheel, "Wheel preset name or JSON file")->capture_default_str();
    command.add_option("--set", set, "Override a soil field in file units, e.g. --set phi_deg=30");
    command.add_option("--a0", a0, "a0 of theta_m = (a0 + a1 s) theta_f (Eq. 2.18)");
    command.add_option("--a1", a1, "a1 of Eq. 2.18");
    auto* jmax =
        command.add_option("--jmax", jmax_m, "Shear deformation limit j_max [m] (Eq. 2.16)");
    command.add_flag("--no-jmax", no_jmax, "No shear deformation limit")->excludes(jmax);
    command.add_option("--bulldozing", bulldozing, "Side-wall pressure coefficients (Eq. 2.27)")
        ->check(CLI::IsMember({"bekker", "hegedus"}))
        ->capture_default_str();
    command.add_option("--model", model, "full (numerical integration) or quadratic (closed form)")
        ->check(CLI::IsMember({"full", "quadratic"}))
        ->capture_default_str();
    if (with_geometry) {
        command.add_option("--max-stress-angle", max_stress_angle_deg,
                           "Fix theta_m [deg] instead of Eq. 2.18");
        auto* exit = command.add_option("--exit-angle", exit_angle_deg,
                                        "Exit angle theta_r [deg], <= 0 (default 0)");
        command
            .add_option("--rut-ratio", rut_ratio, "Rut ratio lambda = h_r/h_f in [0, 1] (Eq. 2.12)")
            ->excludes(exit);
    }
}

soil::SoilParameters ModelOptions::soilParameters(const io::PresetLocations& locations) const {
    Result<soil::SoilParameters> resolved = io::resolveSoil(locations, soil);
    if (!resolved) throw InputError(resolved.message());
    soil::SoilParameters out = resolved.value();
    refuseRepeatedKeys("--set", set);
    std::vector<Issue> issues;
    for (const std::string& assignment : set) {
        const auto equals = assignment.find('=');
        const std::string key = assignment.substr(0, equals);
        const soil::SoilField* field = soil::findSoilField(key);
        double value = 0.0;
        if (!field) {
            std::string keys;
            for (const auto& f : soil::soilFields())
                keys += (keys.empty() ? "" : ", ") + std::string(f.key);
            issues.push_back({"--set " + key, "unknown soil field; fields: " + keys});
        } else if (equals == std::string::npos ||
                   !parseStrictNumber(assignment.substr(equals + 1), value)) {
            issues.push_back(
                {"--set " + key, "expected KEY=NUMBER, got " + io::quoteCell(assignment)});
        } else if (checkRange(issues, "--set " + key, value, field->range, field->displayUnit())) {
            soil::setUserValue(out, *field, value);
        }
    }
    // The flags of optional soil fields: their ranges are the field table's.
    auto flag = [&](const char* name, const char* key, const std::optional<double>& value) {
        const soil::SoilField& field = *soil::findSoilField(key);
        if (value && checkRange(issues, name, *value, field.range, field.displayUnit()))
            field.setUserValue(out, *value);
    };
    flag("--a0", "a0", a0);
    flag("--a1", "a1", a1);
    flag("--jmax", "jmax_m", jmax_m);
    if (no_jmax) out.max_shear_deformation_m = std::numeric_limits<double>::infinity();
    for (Issue& issue : soil::validate(out, "soil ")) issues.push_back(std::move(issue));
    if (!issues.empty()) throw InputError(formatIssues(issues));
    return out;
}

wheel::WheelParameters ModelOptions::wheelParameters(const io::PresetLocations& locations) const {
    Result<wheel::WheelParameters> resolved = io::resolveWheel(locations, wheel);
    if (!resolved) throw InputError(resolved.message());
    return resolved.value();
}

contact::BulldozingModel ModelOptions::bulldozingModel() const {
    return bulldozing == "hegedus" ? contact::BulldozingModel::kHegedus
                                   : contact::BulldozingModel::kBekker;
}

contact::ContactModel ModelOptions::contactModel() const {
    return model == "quadratic" ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
}

contact::ExitCondition ModelOptions::exitCondition() const {
    std::vector<Issue> issues;
    if (rut_ratio) {
        checkRange(issues, "--rut-ratio", *rut_ratio, contact::rutRatioField().range);
        if (!issues.empty()) throw InputError(formatIssues(issues));
        return {contact::ExitCondition::Kind::kRutRatio, *rut_ratio};
    }
    const double deg = exit_angle_deg.value_or(0.0);
    checkRange(issues, "--exit-angle", deg, contact::exitAngleField().range, "deg");
    if (!issues.empty()) throw InputError(formatIssues(issues));
    return {contact::ExitCondition::Kind::kAngle, units::degToRad(deg)};
}

std::optional<double> ModelOptions::maxStressAngleRad() const {
    if (!max_stress_angle_deg) return std::nullopt;
    std::vector<Issue> issues;
    checkRange(issues, "--max-stress-angle", *max_stress_angle_deg,
               contact::maxStressAngleField().range, "deg");
    if (!issues.empty()) throw InputError(formatIssues(issues));
    return units::degToRad(*max_stress_angle_deg);
}

analysis::ModelChoices ModelOptions::choices() const {
    return {exitCondition(), maxStressAngleRad(), bulldozingModel()};
}

analysis::Inputs ModelOptions::inputs(const io::PresetLocations& locations) const {
    analysis::Inputs in{soilParameters(locations), wheelParameters(locations), {}};
    in.conditions.quadratic = contactModel() == contact::ContactModel::kQuadratic;
    return in;
}

std::string numberProblem(const std::string& text, bool whole, bool non_negative) {
    std::size_t begin = text.find_first_not_of(" \t");
    if (begin == std::string::npos) return "empty value; give a number";
    const std::string s = text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
    const std::string quoted = io::quoteCell(s);
    if (non_negative && s[0] == '-') return quoted + " is negative; give a whole number >= 0";
    if (whole) {
        const std::size_t digits = s[0] == '+' || s[0] == '-' ? 1 : 0;
        if (digits == s.size() || s.find_first_not_of("0123456789", digits) != std::string::npos) {
            return quoted + " is not a whole number in decimal digits";
        }
        return {};
    }
    double value = 0.0;
    if (!io::parseNumber(s, value)) {
        const char* first = s.c_str() + (s[0] == '+' ? 1 : 0);
        const auto [end, error] = std::from_chars(first, s.c_str() + s.size(), value);
        if (error == std::errc::result_out_of_range && end == s.c_str() + s.size()) {
            return quoted +
                   (std::abs(std::strtod(first, nullptr)) < 1.0 ? " underflows" : " overflows") +
                   " a double";
        }
        if (error == std::errc{} && end == s.c_str() + s.size())
            return quoted + " is not a finite number";
        return quoted + " is not a decimal number";
    }
    if (value != 0.0 && std::abs(value) < std::numeric_limits<double>::min()) {
        return quoted + " is subnormal (magnitude below 2.2e-308), too small to compute with";
    }
    return {};
}

namespace {

// A whole number checked by numberProblem, without blanks, '+' and leading zeros.
std::string plainInteger(const std::string& text) {
    const std::size_t begin = text.find_first_not_of(" \t+");
    const std::size_t end = text.find_last_not_of(" \t") + 1;
    const bool negative = text[begin] == '-';
    const std::size_t start = begin + (negative ? 1 : 0);
    const std::string digits = text.substr(start, end - start);
    const std::size_t first = digits.find_first_not_of('0');
    if (first == std::string::npos) return "0";
    return (negative ? "-" : "") + digits.substr(first);
}

}  // namespace

bool parseStrictNumber(const std::string& text, double& value) {
    return numberProblem(text).empty() && io::parseNumber(text, value);
}

void makeOptionsStrict(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        if (option->get_type_size() == 0) continue;  // a flag: no value
        const std::string type = option->get_type_name();
        const bool unsigned_type = type.rfind("UINT", 0) == 0;
        const bool integer = unsigned_type || type.rfind("INT", 0) == 0;
        const bool number = integer || type.rfind("FLOAT", 0) == 0;
        // A transform, run before the option's own checks: the number's text is made plain
        // decimal ("010" → "10") for CLI11's conversion, which reads C literals.
        option->transform(CLI::Validator(
            [number, integer, unsigned_type](std::string& value) -> std::string {
                if (!number) {
                    return value.empty() ? std::string("empty value") : std::string();
                }
                const std::string problem = numberProblem(value, integer, unsigned_type);
                if (problem.empty() && integer) value = plainInteger(value);
                return problem;
            },
            ""));
    }
    for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
        makeOptionsStrict(*command);
}

void refuseRepeatedKeys(const std::string& flag, const std::vector<std::string>& items) {
    for (std::size_t i = 0; i < items.size(); ++i) {
        const auto equals = items[i].find('=');
        if (equals == std::string::npos) continue;
        const std::string key = items[i].substr(0, equals);
        for (std::size_t k = 0; k < i; ++k) {
            if (items[k].find('=') != equals || items[k].compare(0, equals, key) != 0) continue;
            throw InputError(flag + " " + key + ": given twice (" + io::quoteCell(items[k]) +
                             " and " + io::quoteCell(items[i]) +
                             "); give each key once, the last would silently win");
        }
    }
}

std::vector<double> parseValues(const std::string& text, const std::string& what) {
    auto number = [&](const std::string& cell) {
        const std::string problem = numberProblem(cell);
        if (!problem.empty()) {
            throw InputError(what + ": " + problem +
                             " (expected a value, a list a,b,c or a range first:last:count)");
        }
        double value = 0.0;
        io::parseNumber(cell, value);
        return value;
    };
    std::vector<std::string> parts;
    const char separator = text.find(':') != std::string::npos ? ':' : ',';
    std::stringstream stream(text);
    for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
    if (parts.empty()) throw InputError(what + ": empty value");
    if (separator == ':') {
        if (parts.size() != 3)
            throw InputError(what + ": a range is first:last:count, got " + io::quoteCell(text));
        const double count = number(parts[2]);
        if (count < 1 || count > 100000 || count != std::floor(count)) {
            throw InputError(what + ": count " + parts[2] +
                             " must be a whole number in [1, 100000]");
        }
        return analysis::linspace(number(parts[0]), number(parts[1]), static_cast<int>(count));
    }
    std::vector<double> values;
    for (const std::string& part : parts) values.push_back(number(part));
    return values;
}

std::vector<NamedInput> ModelOptions::inputFiles() const {
    return {{"--soil", soil}, {"--wheel", wheel}};
}

void nameFlags(std::vector<Issue>& issues,
               const std::vector<std::pair<std::string, std::string>>& keys_to_flags) {
    for (Issue& issue : issues) {
        // The longest key first, so that "slip_angle_deg" is not read as "slip".
        std::size_t best = 0;
        const std::pair<std::string, std::string>* match = nullptr;
        for (const auto& pair : keys_to_flags) {
            if (issue.where.rfind(pair.first, 0) == 0 && pair.first.size() > best) {
                best = pair.first.size();
                match = &pair;
            }
        }
        if (match) issue.where = match->second + issue.where.substr(match->first.size());
    }
}

void refuseInputAsOutput(const std::string& flag, const std::filesystem::path& output,
                         const std::vector<NamedInput>& inputs) {
    if (output.empty() || output == "-") return;
    for (const NamedInput& input : inputs) {
        std::error_code ec;
        if (input.path.empty() || !std::filesystem::equivalent(output, input.path, ec) || ec)
            continue;
        throw InputError(flag + " '" + pathTail(output.string()) + "' is the input " + input.flag +
                         " '" + pathTail(input.path.string()) +
                         "': writing it would replace the input; choose another file");
    }
}

void printLines(const std::vector<std::string>& lines, const std::string& prefix) {
    const std::size_t shown = std::min(lines.size(), kMaxIssuesShown);
    for (std::size_t i = 0; i < shown; ++i)
        std::cerr << formatIssue({"", prefix + lines[i]}) << '\n';
    if (shown < lines.size()) std::cerr << moreIssues(shown, lines.size(), "lines") << '\n';
}

void writeOutput(const std::string& path, const std::string& content) {
    if (path.empty() || path == "-") {
        std::cout << content;
        std::cout.flush();
        return;
    }
    if (const auto error = io::writeFileAtomically(path, content)) throw std::runtime_error(*error);
}

std::filesystem::path executableDirectory() {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::filesystem::path() : exe.parent_path();
}

std::string fixed(double value, int decimals) { return formatFixed(value, decimals); }

void printSummaryRow(std::ostream& out, const analysis::SummaryRow& row) {
    using Emphasis = analysis::SummaryRow::Emphasis;
    std::string line = row.emphasis == Emphasis::kNormal ? "  " + row.label : row.label;
    if (!row.value.empty()) line += ": " + row.value;
    if (!row.unit.empty()) line += " " + row.unit;
    if (!row.detail.empty()) line += " (" + row.detail + ")";
    if (row.emphasis == Emphasis::kHeading && row.value.empty()) line += ":";
    out << line << '\n';
}

void printSummary(std::ostream& out, const analysis::Summary& summary) {
    for (const analysis::SummaryRow& row : summary) printSummaryRow(out, row);
}

}  // namespace terra::app
