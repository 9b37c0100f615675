#include "core/project/script.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/io/json.h"
#include "core/io/json_reader.h"

namespace terra::project {
namespace {

namespace fs = std::filesystem;
using io::ObjectReader;
using io::Presence;
using nlohmann::json;

const Range kImageSide{200.0, 8000.0};  // [px], as `render --width/--height`
const Range kDpi{30.0, 1200.0};

std::string describeAt(const std::vector<std::pair<std::string, double>>& at, const Table& table,
                       const std::vector<double>& row) {
    std::string text;
    for (const auto& [key, value] : at) {
        (void)value;
        text += (text.empty() ? " at " : ", ") + key + " = " + formatNumber(row[table.column(key)]);
    }
    return text;
}

bool hasColumn(const Table& table, const std::string& name) {
    return std::find(table.columns.begin(), table.columns.end(), name) != table.columns.end();
}

// The soil or wheel at `key`: a preset name or a file (relative to the script).
template <typename T, typename Resolve>
std::optional<T> readPreset(ObjectReader& r, const char* key, const std::string& fallback,
                            const fs::path& base_dir, Resolve resolve) {
    std::string name = fallback;
    if (const json* v = r.value(key); v != nullptr && !v->is_string()) {
        r.report(key, "expected a preset name or a JSON file, got " + io::describeJson(*v));
        return std::nullopt;
    }
    r.text(key, name);
    Result<T> resolved = resolve(analysis::ReadContext{nullptr, base_dir}.presetOrFile(name));
    if (!resolved) {
        for (const Issue& issue : resolved.issues())
            r.report(key, (issue.where.empty() ? "" : issue.where + ": ") + issue.message);
        return std::nullopt;
    }
    return resolved.value();
}

// "set": soil fields in file units over `soil`.
void readSet(ObjectReader& r, soil::SoilParameters& soil) {
    ObjectReader set = r.object("set");
    for (const soil::SoilField& field : soil::soilFields()) set.field(field, soil.*field.member);
    set.finish();
}

// What the analyses share unless they give their own: the script's soil, set, wheel, conditions.
struct Shared {
    std::optional<soil::SoilParameters> soil;  // before "set"
    std::optional<json> set;
    std::optional<wheel::WheelParameters> wheel;
    analysis::OperatingConditions conditions;
};

std::vector<Expectation> readExpectations(ObjectReader& r, const analysis::AnalysisType* type) {
    std::vector<Expectation> out;
    const json* list = r.array("expect");
    if (list == nullptr) return out;
    for (std::size_t i = 0; i < list->size(); ++i) {
        ObjectReader e = r.element("expect", *list, i);
        if (!e.isObject()) continue;
        Expectation x;
        e.text("column", x.column, Presence::kRequired);
        if (e.text("table", x.table) && type != nullptr &&
            std::find(type->tables.begin(), type->tables.end(), x.table) == type->tables.end()) {
            std::string names;
            for (const std::string& t : type->tables) names += (names.empty() ? "" : ", ") + t;
            const std::string near = nearestName(x.table, type->tables);
            e.report("table", quoteText(x.table, '"') + " is not a table of " + type->name + " (" +
                                  names + ")" +
                                  (near.empty() ? "" : "; did you mean \"" + near + "\"?"));
        }
        e.text("why", x.why);
        if (e.has("at")) {
            ObjectReader at = e.object("at");
            if (at.isObject()) {
                for (const auto& [column, value] : e.value("at")->items()) {
                    double v = 0.0;
                    if (at.number(column, v, {-1e300, 1e300})) x.at.emplace_back(column, v);
                }
            }
            at.finish();
        }
        const Range any{-1e300, 1e300};
        const bool has_min = e.has("min"), has_max = e.has("max");
        const bool has_value = e.has("value"), has_tolerance = e.has("tolerance");
        bool ok = e.number("min", x.min, any) || !has_min;
        ok = (e.number("max", x.max, any) || !has_max) && ok;
        double value = 0.0, tolerance = 0.0;
        ok = (e.number("value", value, any) || !has_value) && ok;
        ok = (e.number("tolerance", tolerance, {0.0, 1e300}) || !has_tolerance) && ok;
        if ((has_min || has_max) && (has_value || has_tolerance)) {
            e.report({}, "give min/max or value/tolerance, not both");
        } else if (has_value != has_tolerance) {
            e.report({}, "\"value\" needs \"tolerance\" (and the other way round)");
        } else if (has_value) {
            x.min = value - tolerance;
            x.max = value + tolerance;
        } else if (!has_min && !has_max) {
            e.report({}, "needs \"min\", \"max\" or \"value\" and \"tolerance\"");
        } else if (ok && !(x.min <= x.max)) {
            e.report("min", formatNumber(x.min) + " is greater than max = " + formatNumber(x.max));
        }
        e.finish();
        out.push_back(std::move(x));
    }
    return out;
}

std::vector<analysis::FigureSpec> readFigures(ObjectReader& r, const analysis::AnalysisType& type) {
    std::vector<std::string> keys;
    for (const analysis::FigureSpec& f : type.figures) keys.push_back(f.key);
    std::vector<std::string> wanted;
    if (!r.texts("plots", wanted)) return type.figures;
    std::vector<analysis::FigureSpec> out;
    for (std::size_t i = 0; i < wanted.size(); ++i) {
        const auto it = std::find(keys.begin(), keys.end(), wanted[i]);
        if (it == keys.end()) {
            std::string names;
            for (const std::string& k : keys) names += (names.empty() ? "" : ", ") + k;
            const std::string near = nearestName(wanted[i], keys);
            r.report("plots[" + std::to_string(i) + "]",
                     quoteText(wanted[i], '"') + " is not one of " +
                         (names.empty() ? "(none)" : names) +
                         (near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
            continue;
        }
        out.push_back(type.figures[static_cast<std::size_t>(it - keys.begin())]);
    }
    return out;
}

// Whether a name can start file names in the output directory: no control character (a line
// break in a file name breaks every listing and script that reads one), no path separator.
bool fileSafe(const std::string& name) {
    const bool control = std::any_of(name.begin(), name.end(), [](char c) {
        return static_cast<unsigned char>(c) < 0x20 || c == '\x7f';
    });
    return !name.empty() && name[0] != '.' && name.find('/') == std::string::npos &&
           name.find('\\') == std::string::npos && name.size() <= 100 && !control;
}

}  // namespace

ExpectationOutcome check(const Expectation& e, const Table& table) {
    ExpectationOutcome out;
    const std::string range = "[" + formatNumber(e.min) + ", " + formatNumber(e.max) + "]";
    if (!hasColumn(table, e.column)) {
        out.text = e.column + ": no such column in the results";
        return out;
    }
    std::vector<const std::vector<double>*> rows;
    for (const auto& row : table.rows) rows.push_back(&row);
    for (const auto& [key, value] : e.at) {
        if (!hasColumn(table, key)) {
            out.text = quoteText(e.column, '"') + ": no column " + quoteText(key, '"') +
                       " to select the row by";
            return out;
        }
        const std::size_t k = table.column(key);
        double best = INFINITY;
        for (const auto* row : rows) best = std::min(best, std::abs((*row)[k] - value));
        // The target is copied: clang 14 cannot capture a structured binding.
        std::erase_if(rows, [&, target = value](const auto* row) {
            return std::abs((*row)[k] - target) > best;
        });
    }
    if (rows.empty()) {
        out.text = e.column + ": the results have no rows (no equilibrium?)";
        return out;
    }
    const std::vector<double>& row = *rows.front();
    const double value = row[table.column(e.column)];
    out.passed = std::isfinite(value) && value >= e.min && value <= e.max;
    out.text = e.column + describeAt(e.at, table, row) + ": " + formatNumber(value) +
               (out.passed ? " in " : " NOT in ") + range;
    return out;
}

std::vector<ExpectationOutcome> evaluate(const std::vector<Expectation>& expectations,
                                         const analysis::Outcome& outcome) {
    std::vector<ExpectationOutcome> out;
    for (const Expectation& e : expectations) {
        const Table* table = outcome.table(e.table);
        if (table == nullptr) {
            out.push_back({quoteText(e.column, '"') + ": the analysis has no table " +
                               quoteText(e.table, '"'),
                           false});
        } else {
            out.push_back(check(e, *table));
        }
    }
    return out;
}

const std::vector<std::string>& imageFormats() {
    static const std::vector<std::string> formats{"png", "svg", "pdf"};
    return formats;
}

Result<Script> scriptFromJson(const json& document, const std::string& where,
                              const io::PresetLocations& locations, const fs::path& base_dir) {
    std::vector<Issue> issues;
    ObjectReader r(document, issues, where);
    if (!r.isObject()) return issues;
    Script script;
    script.source = document;
    r.text("title", script.title);

    ObjectReader e = r.object("export");
    ExportSettings& x = script.export_settings;
    e.integer("width", x.width, static_cast<int>(kImageSide.low),
              static_cast<int>(kImageSide.high));
    e.integer("height", x.height, static_cast<int>(kImageSide.low),
              static_cast<int>(kImageSide.high));
    e.integer("dpi", x.dpi, static_cast<int>(kDpi.low), static_cast<int>(kDpi.high));
    if (const json* formats = e.array("formats")) {
        std::vector<std::string> names;
        if (formats->empty()) e.report("formats", "needs at least one of png, svg, pdf");
        for (std::size_t i = 0; i < formats->size(); ++i) {
            std::string name;
            const json& f = (*formats)[i];
            if (!f.is_string() || std::find(imageFormats().begin(), imageFormats().end(),
                                            f.get<std::string>()) == imageFormats().end()) {
                e.report("formats[" + std::to_string(i) + "]",
                         io::quoteJson(f) + " is not one of png, svg, pdf");
            } else {
                names.push_back(f.get<std::string>());
            }
        }
        if (!names.empty()) x.formats = names;
    }
    e.finish();

    // The shared inputs, read once (their problems reported once, at the top level).
    Shared shared;
    shared.soil = readPreset<soil::SoilParameters>(
        r, "soil", "sandy-loam", base_dir,
        [&](const std::string& name) { return io::resolveSoil(locations, name); });
    if (r.has("set")) {
        shared.set = document["set"];
        soil::SoilParameters probe = shared.soil.value_or(soil::SoilParameters{});
        readSet(r, probe);
    } else {
        r.allow("set");
    }
    shared.wheel = readPreset<wheel::WheelParameters>(
        r, "wheel", "A", base_dir,
        [&](const std::string& name) { return io::resolveWheel(locations, name); });
    ObjectReader conditions = r.object("conditions");
    analysis::readConditions(conditions, shared.conditions);
    conditions.finish();

    const json* analyses = r.array("analyses", Presence::kRequired);
    const analysis::ReadContext context{&locations, base_dir};
    for (std::size_t i = 0; analyses != nullptr && i < analyses->size(); ++i) {
        ObjectReader a = r.element("analyses", *analyses, i);
        if (!a.isObject()) continue;
        ScriptAnalysis item;
        std::string type_name;
        const bool typed =
            a.choiceName("type", type_name, analysis::analysisTypeNames(), Presence::kRequired);
        item.type = typed ? analysis::findAnalysisType(type_name) : nullptr;
        item.name = type_name.empty() ? "analysis-" + std::to_string(i) : type_name;
        a.text("name", item.name);
        if (!fileSafe(item.name)) {
            a.report("name", quoteText(item.name, '"') +
                                 " cannot start a file name (empty, a leading '.', a '/' or "
                                 "'\\', a control character such as a line break, or longer than "
                                 "100 characters)");
        }
        // The run's own files: an analysis's NAME.json or NAME.md would overwrite them.
        if (item.name == "manifest" || item.name == "report") {
            a.report("name", quoteText(item.name, '"') +
                                 " is reserved: the run writes manifest.json and report.md");
        }
        for (std::size_t j = 0; j < i && j < script.analyses.size(); ++j) {
            if (script.analyses[j].name == item.name) {
                a.report("name", quoteText(item.name, '"') + " is also the name of analyses[" +
                                     std::to_string(j) +
                                     "]: their files would overwrite each other");
            }
        }
        std::string title;
        if (a.text("title", title)) item.title = title;
        item.expectations = readExpectations(a, item.type);
        if (item.type == nullptr) {
            script.analyses.push_back(std::move(item));
            continue;  // without a type its other keys cannot be checked
        }
        item.figures = readFigures(a, *item.type);
        if (item.type->uses_inputs) {
            const std::size_t before = issues.size();
            std::optional<soil::SoilParameters> soil =
                a.has("soil")
                    ? readPreset<soil::SoilParameters>(
                          a, "soil", "", base_dir,
                          [&](const std::string& n) { return io::resolveSoil(locations, n); })
                    : shared.soil;
            if (soil && a.has("set")) {
                readSet(a, *soil);
            } else if (soil && shared.set) {
                // The script's "set" (its problems were reported at the top level).
                std::vector<Issue> reported;
                ObjectReader set(*shared.set, reported);
                for (const soil::SoilField& field : soil::soilFields())
                    set.field(field, (*soil).*field.member);
                a.allow("set");
            } else {
                a.allow("set");
            }
            std::optional<wheel::WheelParameters> wheel =
                a.has("wheel")
                    ? readPreset<wheel::WheelParameters>(
                          a, "wheel", "", base_dir,
                          [&](const std::string& n) { return io::resolveWheel(locations, n); })
                    : shared.wheel;
            item.inputs.conditions = shared.conditions;
            ObjectReader own = a.object("conditions");
            analysis::readConditions(own, item.inputs.conditions);
            own.finish();
            if (soil && wheel && issues.size() == before) {
                item.inputs.soil = *soil;
                item.inputs.wheel = *wheel;
                // The soil after "set" and the soil on this wheel (K_s = k_c/b + k_φ > 0).
                for (const Issue& issue : analysis::validate(item.inputs))
                    a.report(issue.where, issue.message);
            }
        }
        item.settings = item.type->read(a, context);
        a.finish();
        script.analyses.push_back(std::move(item));
    }
    r.finish();
    if (!issues.empty()) return issues;
    return script;
}

Result<Script> loadScript(const fs::path& path, const io::PresetLocations& locations) {
    return io::readJsonFileWith<Script>(path, [&](const json& document, const std::string& source) {
        return scriptFromJson(document, source, locations, path.parent_path());
    });
}

int failureCount(const std::vector<RunRecord>& records) {
    int failed = 0;
    for (const RunRecord& r : records) {
        if (!r.error.empty()) ++failed;
        for (const ExpectationOutcome& o : r.outcomes) failed += o.passed ? 0 : 1;
    }
    return failed;
}

std::string reportMarkdown(const Script& script, const std::string& script_path,
                           const std::vector<RunRecord>& records, const std::string& cancelled) {
    const int failed = failureCount(records);
    std::ostringstream md;
    md << "# " << script.title << "\n\n";
    md << "Script: `" << script_path << "`  \n";
    if (!cancelled.empty()) md << "**" << cancelled << ".**  \n";
    md << (failed == 0 ? "**All expectations met.**"
                       : "**" + std::to_string(failed) + " expectation(s) or analyses FAILED.**")
       << "\n\n";
    if (failed > 0) {
        md << "## Failures\n\n";
        for (const auto& r : records) {
            if (!r.error.empty()) md << "- `" << r.name << "`: " << r.error << "\n";
            for (const auto& o : r.outcomes) {
                if (!o.passed) md << "- `" << r.name << "`: " << o.text << "\n";
            }
        }
        md << "\n";
    }
    for (const auto& r : records) {
        md << "## " << r.name << " (" << r.type << ")\n\n";
        if (!r.error.empty()) md << "**Error:** " << r.error << "\n\n";
        if (!r.outcomes.empty()) {
            md << "| Expectation | Result |\n|---|---|\n";
            for (const auto& o : r.outcomes)
                md << "| " << o.text << " | " << (o.passed ? "pass" : "**FAIL**") << " |\n";
            md << "\n";
        }
        for (const auto& image : r.images) {
            if (image.ends_with(".png") || image.ends_with(".svg"))
                md << "![" << image << "](" << image << ")\n\n";
        }
        if (!r.data.empty()) {
            md << "Data:";
            for (const auto& d : r.data) md << " [" << d << "](" << d << ")";
            md << "\n\n";
        }
        for (const auto& note : r.notes) md << "- " << note << "\n";
        if (!r.notes.empty()) md << "\n";
        md << "_" << formatNumber(std::round(r.seconds * 1000.0) / 1000.0) << " s_\n\n";
    }
    return md.str();
}

json manifest(const Script& script, const std::string& script_path,
              const std::vector<RunRecord>& records, const std::string& tool,
              const std::string& cancelled) {
    json out{{"tool", tool},
             {"script", script_path},
             {"inputs", script.source},
             {"failed", failureCount(records)},
             {"analyses", json::array()}};
    if (!cancelled.empty()) out.update({{"cancelled", true}, {"note", cancelled}});
    for (const auto& r : records) {
        json outcomes = json::array();
        for (const auto& o : r.outcomes)
            outcomes.push_back({{"text", o.text}, {"passed", o.passed}});
        out["analyses"].push_back({{"name", r.name},
                                   {"type", r.type},
                                   {"images", r.images},
                                   {"data", r.data},
                                   {"error", r.error},
                                   {"expectations", outcomes},
                                   {"notes", r.notes}});
    }
    return out;
}

}  // namespace terra::project
