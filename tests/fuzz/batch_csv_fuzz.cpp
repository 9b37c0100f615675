// Fuzz harness: the batch CSV of `terrastudio wheel --input` (app/cli/wheel_command.cpp): the CSV
// reader (io::parseCsv) and, for every row, the cell reader (io::readCell) of each column the
// batch reads, with the operating point's field table as the ranges (contact/operating_fields.h),
// as the command does. The row's evaluation (the wheel model) is not fuzzed here.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/contact/operating_fields.h"
#include "core/io/csv.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(batch_csv) {
    using namespace terra;
    static const std::vector<io::NumericColumn> kColumns = {
        io::numericColumn(contact::slipField()),
        io::numericColumn(contact::slipAngleField()),
        io::numericColumn(contact::entryAngleField()),
        io::numericColumn(contact::loadField()),
        io::numericColumn(contact::exitAngleField()),
        io::numericColumn(contact::rutRatioField()),
        io::numericColumn(contact::maxStressAngleField()),
    };
    const Result<io::CsvDocument> read = io::parseCsv(fuzz::textOf(data, size), "fuzz.csv");
    fuzz::checkResult(read);
    if (!read) return 0;
    const io::CsvDocument& doc = *read;
    if (doc.rows.size() != doc.line_numbers.size())
        fuzz::fail("rows and line numbers differ in count");
    for (std::size_t row = 0; row < doc.rows.size(); ++row) {
        if (doc.rows[row].size() != doc.header.size()) fuzz::fail("a row of the wrong width kept");
        const std::string where = "fuzz.csv:" + std::to_string(doc.line_numbers[row]);
        for (const io::NumericColumn& column : kColumns) {
            for (std::size_t c = 0; c < doc.header.size(); ++c) {
                if (doc.header[c] != column.name) continue;
                std::vector<Issue> issues;
                const std::optional<double> value =
                    io::readCell(doc.rows[row][c], column, where, issues);
                if (value.has_value() == !issues.empty())
                    fuzz::fail("readCell: a value and issues, or neither");
                if (value && !(column.range.contains(*value) && std::isfinite(*value)))
                    fuzz::fail("readCell: a value outside the column's range");
                fuzz::checkResult(value ? Result<double>(*value) : Result<double>(issues));
            }
        }
    }
    return 0;
}
