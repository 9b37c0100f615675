#include "core/common/table.h"

#include <algorithm>
#include <stdexcept>

namespace terra {

std::size_t Table::column(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end()) throw std::out_of_range("no column '" + name + "'");
    return static_cast<std::size_t>(it - columns.begin());
}

std::vector<double> Table::values(const std::string& name) const {
    const std::size_t index = column(name);
    std::vector<double> out;
    out.reserve(rows.size());
    for (const auto& row : rows) out.push_back(row[index]);
    return out;
}

}  // namespace terra
