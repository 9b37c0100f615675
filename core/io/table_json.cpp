#include "core/io/table_json.h"

#include <cmath>

namespace terra::io {

nlohmann::json toJson(const Table& table) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& row : table.rows) {
        nlohmann::json object = nlohmann::json::object();
        for (std::size_t i = 0; i < row.size() && i < table.columns.size(); ++i) {
            object[table.columns[i]] =
                std::isfinite(row[i]) ? nlohmann::json(row[i]) : nlohmann::json();
        }
        rows.push_back(std::move(object));
    }
    return rows;
}

}  // namespace terra::io
