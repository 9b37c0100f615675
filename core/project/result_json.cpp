#include "core/project/result_json.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace terra::project::saved {

using nlohmann::json;

json number(double v) {
    if (std::isnan(v)) return nullptr;
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return v;
}

double numberOf(const json& v) {
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (v.is_string()) {
        const std::string text = v.get<std::string>();
        if (text == "inf") return std::numeric_limits<double>::infinity();
        if (text == "-inf") return -std::numeric_limits<double>::infinity();
        throw std::invalid_argument("\"" + text + "\" is not a number");
    }
    if (!v.is_number()) throw std::invalid_argument(v.dump() + " is not a number");
    return v.get<double>();
}

double numberAt(const json& j, const char* key) {
    try {
        return numberOf(j.at(key));
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(key) + ": " + e.what());
    }
}

json tableJson(const Table& table) {
    json rows = json::array();
    for (const std::vector<double>& row : table.rows) {
        json r = json::array();
        for (double v : row) r.push_back(number(v));
        rows.push_back(std::move(r));
    }
    json out{{"columns", table.columns}, {"rows", std::move(rows)}};
    if (!table.label_column.empty()) {
        out["label_column"] = table.label_column;
        out["labels"] = table.labels;
    }
    return out;
}

Table tableFrom(const json& j) {
    Table t;
    t.columns = j.at("columns").get<std::vector<std::string>>();
    for (const json& row : j.at("rows")) {
        std::vector<double> r;
        r.reserve(row.size());
        for (const json& v : row) r.push_back(numberOf(v));
        if (r.size() != t.columns.size())
            throw std::invalid_argument("a row has " + std::to_string(r.size()) + " values for " +
                                        std::to_string(t.columns.size()) + " columns");
        t.rows.push_back(std::move(r));
    }
    if (j.contains("label_column")) {
        t.label_column = j.at("label_column").get<std::string>();
        t.labels = j.at("labels").get<std::vector<std::string>>();
        if (t.labels.size() != t.rows.size())
            throw std::invalid_argument(std::to_string(t.labels.size()) + " labels for " +
                                        std::to_string(t.rows.size()) + " rows");
    }
    return t;
}

json matrixJson(const Eigen::MatrixXd& m) {
    json rows = json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        json row = json::array();
        for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(number(m(i, j)));
        rows.push_back(std::move(row));
    }
    return rows;
}

Eigen::MatrixXd matrixFrom(const json& j) {
    if (!j.is_array()) throw std::invalid_argument("a matrix is an array of rows");
    const auto rows = static_cast<Eigen::Index>(j.size());
    const auto cols = rows == 0 ? Eigen::Index{0} : static_cast<Eigen::Index>(j.front().size());
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i) {
        const json& row = j[static_cast<std::size_t>(i)];
        if (!row.is_array() || static_cast<Eigen::Index>(row.size()) != cols)
            throw std::invalid_argument("matrix rows of different lengths");
        for (Eigen::Index c = 0; c < cols; ++c)
            m(i, c) = numberOf(row[static_cast<std::size_t>(c)]);
    }
    return m;
}

json vectorJson(const Eigen::VectorXd& v) {
    json out = json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number(v(i)));
    return out;
}

Eigen::VectorXd vectorFrom(const json& j) {
    if (!j.is_array()) throw std::invalid_argument("a vector is an array of numbers");
    Eigen::VectorXd v(static_cast<Eigen::Index>(j.size()));
    for (std::size_t i = 0; i < j.size(); ++i) v(static_cast<Eigen::Index>(i)) = numberOf(j[i]);
    return v;
}

}  // namespace terra::project::saved
