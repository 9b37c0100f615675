#include "core/io/table_json.h"

#include <cmath>

namespace terra::io {

nlohmann::json toJson(const Table& table) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& row : table.rows) {
        nlohmann::json object = nlohmann::json::object();
        const auto r = static_cast<std::size_t>(&row - table.rows.data());
        if (!table.label_column.empty() && r < table.labels.size())
            object[table.label_column] = table.labels[r];
        for (std::size_t i = 0; i < row.size() && i < table.columns.size(); ++i) {
            object[table.columns[i]] =
                std::isfinite(row[i]) ? nlohmann::json(row[i]) : nlohmann::json();
        }
        rows.push_back(std::move(object));
    }
    return rows;
}

}  // namespace terra::io
