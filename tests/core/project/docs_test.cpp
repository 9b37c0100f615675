// The user guide's table of run-script settings (docs/user-guide.md, "Scripted runs") against the
// readers themselves: every analysis type has a row, and every key its reader accepts is named in
// that row, so the docs cannot fall behind a new setting or a new analysis.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/analysis/registry.h"
#include "core/io/json_reader.h"

namespace terra::analysis {
namespace {

/// The rows of the table whose header starts with "| type | settings |": type → settings cell.
std::map<std::string, std::string> settingsRows(const std::string& guide_path) {
    std::ifstream in(guide_path);
    EXPECT_TRUE(in) << guide_path;
    std::map<std::string, std::string> rows;
    std::string line;
    bool in_table = false;
    while (std::getline(in, line)) {
        if (line.rfind("| type | settings |", 0) == 0) {
            in_table = true;
            continue;
        }
        if (!in_table) continue;
        if (line.rfind("|---", 0) == 0) continue;
        if (line.rfind("| `", 0) != 0) break;  // the table ended
        const std::size_t type_end = line.find('`', 3);
        const std::size_t cell_start = line.find('|', type_end);
        const std::size_t cell_end = line.find('|', cell_start + 1);
        rows[line.substr(3, type_end - 3)] = line.substr(cell_start + 1, cell_end - cell_start - 1);
    }
    return rows;
}

TEST(UserGuide, NamesEveryAnalysisTypeAndEverySettingItsReaderAccepts) {
    const std::map<std::string, std::string> rows =
        settingsRows(TERRA_RESOURCE_DIR "/../docs/user-guide.md");
    ASSERT_FALSE(rows.empty()) << "no \"| type | settings |\" table in docs/user-guide.md";
    const io::PresetLocations locations{{TERRA_RESOURCE_DIR}};
    const ReadContext context{&locations, TERRA_RESOURCE_DIR "/scripts"};
    // The model choices (readModelChoices) are documented once, in the table's footnote: a row
    // that says "model choices" names them.
    const nlohmann::json none = nlohmann::json::object();
    std::vector<Issue> ignored;
    io::ObjectReader choices(none, ignored);
    ModelChoices unused;
    readModelChoices(choices, unused);
    const std::vector<std::string> choice_keys = choices.knownKeys();
    ASSERT_GE(choice_keys.size(), 3u);
    for (const AnalysisType& type : analysisTypes()) {
        const auto row = rows.find(type.name);
        ASSERT_NE(row, rows.end()) << "docs/user-guide.md has no settings row for " << type.name;
        // Reading an empty object marks every key the reader knows (missing required keys are
        // reported as issues, which do not matter here).
        const nlohmann::json empty = nlohmann::json::object();
        std::vector<Issue> issues;
        io::ObjectReader reader(empty, issues);
        (void)type.read(reader, context);
        EXPECT_FALSE(reader.knownKeys().empty()) << type.name;
        const bool names_choices = row->second.find("model choices") != std::string::npos;
        for (const std::string& key : reader.knownKeys()) {
            if (names_choices &&
                std::find(choice_keys.begin(), choice_keys.end(), key) != choice_keys.end())
                continue;
            EXPECT_NE(row->second.find("`" + key + "`"), std::string::npos)
                << "docs/user-guide.md: the " << type.name << " row does not name `" << key << "`";
        }
    }
    // And no row for a type that does not exist.
    for (const auto& [name, cell] : rows) {
        (void)cell;
        EXPECT_NE(findAnalysisType(name), nullptr) << "docs/user-guide.md documents " << name;
    }
}

}  // namespace
}  // namespace terra::analysis
