#include "core/io/csv.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/table_json.h"
#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using terra::testing::TempDir;

// ---- toCsv -----------------------------------------------------------------------------------

TEST(ToCsv, HeaderThenOneLinePerRow) {
    const Table table{{"slip", "Fx_N"}, {{0.1, 12.5}, {0.2, -3.25}}};
    EXPECT_EQ(toCsv(table), "slip,Fx_N\n0.1,12.5\n0.2,-3.25\n");
}

// A label column comes first, quoted (RFC 4180: doubled quotes) where a label holds a comma or a
// quote, and the parser reads the labels back as they were.
TEST(ToCsv, LabelColumnComesFirstAndRoundTrips) {
    Table table{{"Fx_N"}, {{1.5}, {-2.0}, {kNaN}}};
    table.label_column = "parameter";
    table.labels = {"phi_deg", "a,b", "say \"x\""};
    const std::string text = toCsv(table);
    EXPECT_EQ(text, "parameter,Fx_N\nphi_deg,1.5\n\"a,b\",-2\n\"say \"\"x\"\"\",\n");
    const Result<CsvDocument> doc = parseCsv(text, "labels.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    ASSERT_EQ(doc->rows.size(), 3u);
    EXPECT_EQ(doc->header, (std::vector<std::string>{"parameter", "Fx_N"}));
    EXPECT_EQ(doc->rows[1][0], "a,b");
    EXPECT_EQ(doc->rows[2][0], "say \"x\"");
    EXPECT_EQ(doc->rows[2][1], "");
}

// JSON rows carry the label under the label column's name, beside the numbers (NaN as null).
TEST(TableJson, LabelColumnIsAKeyOfEachRow) {
    Table table{{"Fx_N"}, {{1.5}, {kNaN}}};
    table.label_column = "parameter";
    table.labels = {"phi_deg", "c_kPa"};
    const nlohmann::json rows = toJson(table);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0], (nlohmann::json{{"parameter", "phi_deg"}, {"Fx_N", 1.5}}));
    EXPECT_EQ(rows[1]["parameter"], "c_kPa");
    EXPECT_TRUE(rows[1]["Fx_N"].is_null());
}

TEST(ToCsv, NoRowsGivesOnlyTheHeader) { EXPECT_EQ(toCsv(Table{{"a", "b", "c"}, {}}), "a,b,c\n"); }

TEST(ToCsv, NaNIsAnEmptyCell) {
    const Table table{{"x", "y", "z"}, {{kNaN, 1.0, 2.0}, {3.0, kNaN, 4.0}, {5.0, 6.0, kNaN}}};
    EXPECT_EQ(toCsv(table), "x,y,z\n,1,2\n3,,4\n5,6,\n");
}

TEST(ToCsv, NumbersRoundTripExactly) {
    const std::vector<double> values{0.1,
                                     1.0 / 3.0,
                                     2.0 / 3.0,
                                     0.1 + 0.2,
                                     std::numbers::pi,
                                     -1e-300,
                                     1e300,
                                     std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::min(),
                                     std::numeric_limits<double>::denorm_min(),
                                     123456789.12345679,
                                     58.86};
    Table table{{"value"}, {}};
    for (double v : values) table.rows.push_back({v});
    const Result<CsvDocument> doc = parseCsv(toCsv(table), "round-trip.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    ASSERT_EQ(doc->rows.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        double parsed = 0.0;
        ASSERT_TRUE(parseNumber(doc->rows[i][0], parsed)) << doc->rows[i][0];
        // Bit-identical.
        EXPECT_EQ(std::bit_cast<std::uint64_t>(parsed), std::bit_cast<std::uint64_t>(values[i]))
            << "wrote " << doc->rows[i][0];
    }
}

TEST(ToCsv, NegativeZeroIsWrittenAsZero) {
    // −0 is rounding noise (F_y = −r b · 0 at β = 0), never worth a minus sign in a report.
    EXPECT_EQ(toCsv(Table{{"v"}, {{-0.0}}}), "v\n0\n");
}

// ---- parseCsv --------------------------------------------------------------------------------

TEST(ParseCsv, HeaderAndRowsWithLineNumbers) {
    const Result<CsvDocument> doc = parseCsv("a,b\n1,2\n3,4\n", "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    EXPECT_EQ(doc->header, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(doc->rows, (std::vector<std::vector<std::string>>{{"1", "2"}, {"3", "4"}}));
    EXPECT_EQ(doc->line_numbers, (std::vector<int>{2, 3}));
}

TEST(ParseCsv, LastLineWithoutNewline) {
    const Result<CsvDocument> doc = parseCsv("a,b\n1,2", "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    ASSERT_EQ(doc->rows.size(), 1u);
    EXPECT_EQ(doc->rows[0], (std::vector<std::string>{"1", "2"}));
}

TEST(ParseCsv, HeaderOnlyHasNoRows) {
    const Result<CsvDocument> doc = parseCsv("a,b\n", "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    EXPECT_EQ(doc->header.size(), 2u);
    EXPECT_TRUE(doc->rows.empty());
}

TEST(ParseCsv, QuotedCells) {
    const std::string text =
        "name,value\n"
        "\"sand, dry\",1\n"
        "\"say \"\"hi\"\"\",2\n"
        "\"\",3\n";
    const Result<CsvDocument> doc = parseCsv(text, "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    ASSERT_EQ(doc->rows.size(), 3u);
    EXPECT_EQ(doc->rows[0], (std::vector<std::string>{"sand, dry", "1"}));
    EXPECT_EQ(doc->rows[1], (std::vector<std::string>{"say \"hi\"", "2"}));
    EXPECT_EQ(doc->rows[2], (std::vector<std::string>{"", "3"}));
}

TEST(ParseCsv, CommentsAndBlankLinesAreSkippedButCounted) {
    const std::string text =
        "# measured 2024\n"  // 1
        "\n"                 // 2
        "x,y\n"              // 3
        "# mid comment\n"    // 4
        "1,2\n"              // 5
        "   \n"              // 6
        "  # indented\n"     // 7
        "3,4\n";             // 8
    const Result<CsvDocument> doc = parseCsv(text, "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    EXPECT_EQ(doc->header, (std::vector<std::string>{"x", "y"}));
    EXPECT_EQ(doc->rows, (std::vector<std::vector<std::string>>{{"1", "2"}, {"3", "4"}}));
    EXPECT_EQ(doc->line_numbers, (std::vector<int>{5, 8}));
}

TEST(ParseCsv, ByteOrderMarkIsDropped) {
    const Result<CsvDocument> doc = parseCsv("\xEF\xBB\xBFx,y\n1,2\n", "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    EXPECT_EQ(doc->header, (std::vector<std::string>{"x", "y"}));
    EXPECT_EQ(doc->line_numbers, (std::vector<int>{2}));
}

TEST(ParseCsv, WindowsLineEndingsAndSpacesAreTrimmed) {
    const Result<CsvDocument> doc = parseCsv("x, y\r\n 1 ,2\r\n", "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    EXPECT_EQ(doc->header, (std::vector<std::string>{"x", "y"}));
    EXPECT_EQ(doc->rows, (std::vector<std::vector<std::string>>{{"1", "2"}}));
}

TEST(ParseCsv, RowsWithTheWrongNumberOfCellsAreReportedWithTheirLine) {
    const std::string text =
        "x,y\n"     // 1
        "1,2\n"     // 2
        "\n"        // 3
        "# note\n"  // 4
        "3\n"       // 5: one cell
        "4,5,6\n"   // 6: three cells
        "7,8\n";    // 7
    // The good rows are kept and the bad ones listed, so a caller can stop or skip them.
    const Result<CsvDocument> doc = parseCsv(text, "data.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    const auto& issues = doc->row_issues;
    ASSERT_EQ(issues.size(), 2u);
    EXPECT_EQ(issues[0].where, "data.csv:5");
    EXPECT_EQ(issues[0].message, "1 cells, the header has 2");
    EXPECT_EQ(issues[1].where, "data.csv:6");
    EXPECT_EQ(issues[1].message, "3 cells, the header has 2");
    EXPECT_EQ(formatIssues(issues),
              "data.csv:5: 1 cells, the header has 2\ndata.csv:6: 3 cells, the header has 2");
    ASSERT_EQ(doc->rows.size(), 2u);
    EXPECT_EQ(doc->line_numbers, (std::vector<int>{2, 7}));
}

TEST(ParseCsv, LineNumbersCountTheByteOrderMarkLine) {
    const Result<CsvDocument> doc = parseCsv("\xEF\xBB\xBF# c\nx,y\n1\n", "bom.csv");
    ASSERT_TRUE(doc.ok());
    ASSERT_EQ(doc->row_issues.size(), 1u);
    EXPECT_EQ(doc->row_issues[0].where, "bom.csv:3");
}

TEST(ParseCsv, EmptyFile) {
    for (const std::string text : {"", "\n\n", "# only a comment\n", "\xEF\xBB\xBF"}) {
        const Result<CsvDocument> doc = parseCsv(text, "empty.csv");
        ASSERT_FALSE(doc.ok()) << "'" << text << "'";
        ASSERT_EQ(doc.issues().size(), 1u);
        EXPECT_EQ(doc.issues()[0].where, "empty.csv");
        EXPECT_EQ(doc.issues()[0].message, "empty file: expected a header row");
    }
}

TEST(ReadCsv, ReportsTheFilePathAndLine) {
    TempDir temp;
    const fs::path file = temp.path() / "points.csv";
    std::ofstream(file) << "slip,Fx_N\n0.1,1\n0.2\n";
    const Result<CsvDocument> doc = readCsv(file);
    ASSERT_TRUE(doc.ok());
    ASSERT_EQ(doc->row_issues.size(), 1u);
    EXPECT_EQ(doc->row_issues[0].where, file.string() + ":3");
}

TEST(ReadCsv, MissingFile) {
    TempDir temp;
    const Result<CsvDocument> doc = readCsv(temp.path() / "absent.csv");
    ASSERT_FALSE(doc.ok());
    ASSERT_EQ(doc.issues().size(), 1u);
    EXPECT_EQ(doc.issues()[0].where, (temp.path() / "absent.csv").string());
}

// ---- parseNumber -----------------------------------------------------------------------------

TEST(ParseNumber, RejectsTextThatIsNotAFiniteNumber) {
    for (const char* cell : {"", "   ", "abc", "1.5x", "x1.5", "nan", "NaN", "inf", "-inf",
                             "infinity", "1e400", "1,5", "+", "-", "++2", "1 2"}) {
        double value = 0.0;
        EXPECT_FALSE(parseNumber(cell, value)) << "'" << cell << "' gave " << value;
    }
}

TEST(ParseNumber, AcceptsSignsExponentsAndSurroundingSpaces) {
    struct Case {
        const char* cell;
        double value;
    };
    for (const Case& c :
         {Case{"+2", 2.0}, Case{"-1e-3", -0.001}, Case{"0", 0.0}, Case{" 3.25 ", 3.25},
          Case{"1E3", 1000.0}, Case{"58.86", 58.86}, Case{"\t-0.5\r", -0.5}}) {
        double value = 0.0;
        ASSERT_TRUE(parseNumber(c.cell, value)) << "'" << c.cell << "'";
        EXPECT_EQ(value, c.value) << "'" << c.cell << "'";
    }
}

// Regression: parseNumber() once accepted "+-2" as -2 (it skipped a leading '+' and then let
// std::from_chars read a '-').
TEST(ParseNumber, RejectsPlusFollowedByMinus) {
    double value = 0.0;
    EXPECT_FALSE(parseNumber("+-2", value)) << "gave " << value;
}

// ---- duplicated columns ----------------------------------------------------------------------

TEST(ParseCsv, ADuplicatedColumnFailsTheParseNamingBothPositions) {
    const Result<CsvDocument> doc = parseCsv("# comment\nslip,Fx_N,slip\n0.1,2,0.3\n", "d.csv");
    ASSERT_FALSE(doc.ok());
    ASSERT_EQ(doc.issues().size(), 1u);
    EXPECT_EQ(doc.issues()[0].where, "d.csv:2");
    EXPECT_EQ(doc.issues()[0].message,
              "column 'slip' appears twice (columns 1 and 3); each column may be given once");
}

TEST(ParseCsv, UnnamedColumnsMayRepeat) {
    // Trailing commas from a spreadsheet: columns without a name are never read.
    const Result<CsvDocument> doc = parseCsv("a,b,,\n1,2,,\n", "t.csv");
    ASSERT_TRUE(doc.ok()) << doc.message();
    EXPECT_EQ(doc->rows.size(), 1u);
}

// ---- quoteCell -------------------------------------------------------------------------------

TEST(QuoteCell, ShortTextIsQuotedWhole) {
    EXPECT_EQ(quoteCell("abc"), "'abc'");
    EXPECT_EQ(quoteCell(std::string(80, 'x')), "'" + std::string(80, 'x') + "'");
}

TEST(QuoteCell, LongTextIsCutWithItsLength) {
    const std::string quoted = quoteCell(std::string(200000, '9'));
    EXPECT_EQ(quoted, "'" + std::string(80, '9') + "\u2026' (200000 characters)");
}

TEST(QuoteCell, NeverCutsInsideAUtf8Character) {
    // 79 ASCII bytes, then "°" (2 bytes) straddling the 80-byte cut, then more.
    const std::string text = std::string(79, 'a') + "\u00b0" + std::string(10, 'b');
    EXPECT_EQ(quoteCell(text), "'" + std::string(79, 'a') + "\u2026' (91 characters)");
}

// ---- readCell --------------------------------------------------------------------------------

double degToRad(double deg) { return deg * std::numbers::pi / 180.0; }

const NumericColumn kAngle{"entry_angle_deg", {0.0, 90.0, true, true}, "deg", degToRad};

std::string readError(const std::string& cell, const NumericColumn& column = kAngle) {
    std::vector<Issue> issues;
    const std::optional<double> value = readCell(cell, column, "d.csv:7", issues);
    EXPECT_FALSE(value.has_value()) << "'" << cell << "' gave " << *value;
    if (issues.size() != 1u) return "expected one issue, got " + std::to_string(issues.size());
    EXPECT_EQ(issues[0].where, "d.csv:7");
    return issues[0].message;
}

TEST(ReadCell, GoodCellsGiveTheirValueInTheFileUnit) {
    std::vector<Issue> issues;
    EXPECT_EQ(readCell(" 16.8 ", kAngle, "d.csv:2", issues), 16.8);
    EXPECT_EQ(readCell("+45", kAngle, "d.csv:2", issues), 45.0);
    const NumericColumn force{"Fx_N", {-1e7, 1e7}, "N"};
    EXPECT_EQ(readCell("0", force, "d.csv:2", issues), 0.0);  // zero is not subnormal
    EXPECT_EQ(readCell("-2.5e3", force, "d.csv:2", issues), -2500.0);
    EXPECT_TRUE(issues.empty()) << formatIssues(issues);
}

TEST(ReadCell, EveryBadCellIsNamedWithItsValueAndRange) {
    EXPECT_EQ(readError("abc"),
              "entry_angle_deg = 'abc' is not a number; allowed range (0, 90) deg");
    EXPECT_EQ(readError("+-2"),
              "entry_angle_deg = '+-2' is not a number; allowed range (0, 90) deg");
    EXPECT_EQ(readError(""), "entry_angle_deg = '' is not a number; allowed range (0, 90) deg");
    EXPECT_EQ(readError("nan"),
              "entry_angle_deg = 'nan' is not a finite number; allowed range (0, 90) deg");
    EXPECT_EQ(readError("-inf"),
              "entry_angle_deg = '-inf' is not a finite number; allowed range (0, 90) deg");
    EXPECT_EQ(readError("1e999"),
              "entry_angle_deg = '1e999' overflows a double; allowed range (0, 90) deg");
    EXPECT_EQ(readError("1e-400"),
              "entry_angle_deg = '1e-400' underflows a double; allowed range (0, 90) deg");
    EXPECT_EQ(readError("95"), "entry_angle_deg = 95 is outside the allowed range (0, 90) deg");
    EXPECT_EQ(readError("0"), "entry_angle_deg = 0 is outside the allowed range (0, 90) deg");
}

// The issue's case: 1e-320 passed the (0, 90) check and became 0 rad.
TEST(ReadCell, SubnormalsAreRejected) {
    EXPECT_EQ(readError("1e-320"),
              "entry_angle_deg = '1e-320' is subnormal (magnitude below 2.2e-308), too small to "
              "compute with; allowed range (0, 90) deg");
    const NumericColumn force{"Fx_N", {-1e7, 1e7}, "N"};
    EXPECT_NE(readError("-4.9e-324", force).find("is subnormal"), std::string::npos);
}

// 1e-307 deg is a normal double, but 1.7e-309 rad is not: the SI value is checked too.
TEST(ReadCell, AnSiValueThatUnderflowsOrOverflowsIsRejected) {
    EXPECT_EQ(readError("1e-307"),
              "entry_angle_deg = 1e-307 deg underflows when converted to SI units "
              "(1.74532925199433e-309); allowed range (0, 90) deg");
    const NumericColumn huge{"x_km", {0.0, 1e308}, "km", [](double km) { return km * 1e3; }};
    EXPECT_EQ(readError("1e306", huge),
              "x_km = 1e+306 km overflows when converted to SI units (inf); allowed range [0, "
              "1e+308] km");
}

TEST(ReadCell, AHugeCellIsQuotedShort) {
    const std::string message = readError(std::string(200000, '7'));
    EXPECT_LT(message.size(), 200u) << message.size();
    EXPECT_NE(message.find("(200000 characters) overflows a double"), std::string::npos) << message;
}

// Issue 28: CR-only files (old Mac, some loggers) were one header line.
TEST(ParseCsv, CrAloneCrLfAndLfAllEndLines) {
    for (const std::string eol : {"\n", "\r\n", "\r"}) {
        const auto doc = parseCsv("a,b" + eol + "1,2" + eol + eol + "3,4" + eol, "f.csv");
        ASSERT_TRUE(doc.ok()) << doc.message();
        ASSERT_EQ(doc->rows.size(), 2u);
        EXPECT_EQ(doc->rows[1], (std::vector<std::string>{"3", "4"}));
        EXPECT_EQ(doc->line_numbers, (std::vector<int>{2, 4}));
    }
}

TEST(ParseCsv, AnUnbalancedQuoteIsNamedWithItsColumn) {
    auto doc = parseCsv("a,b,c\n1,2,\"x\n4,5,6\n", "f.csv");
    ASSERT_TRUE(doc.ok());
    ASSERT_EQ(doc->row_issues.size(), 1u);
    EXPECT_EQ(doc->row_issues[0].where, "f.csv:2");
    EXPECT_NE(
        doc->row_issues[0].message.find("unbalanced double quote: the quoted cell in column 3"),
        std::string::npos);
    EXPECT_EQ(doc->rows.size(), 1u);
    doc = parseCsv("a,\"b\n1,2\n", "f.csv");
    ASSERT_FALSE(doc.ok());
    EXPECT_NE(doc.message().find("f.csv:1: header: unbalanced double quote"), std::string::npos);
}

TEST(CheckColumns, ANearNameOfAMissingColumnIsAnErrorAnyOtherAWarning) {
    const std::vector<std::string> known{"slip", "load_N"};
    ColumnCheck c = checkColumns({"slp", "load_N", "id"}, known, "p.csv:1", "copied");
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_NE(c.errors[0].message.find("unknown column 'slp'; did you mean slip?"),
              std::string::npos);
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_NE(c.warnings[0].message.find("column 'id' is not read"), std::string::npos);
    c = checkColumns({"slip", "Slip", "load_N"}, known, "p.csv:1", "");
    EXPECT_TRUE(c.errors.empty());  // slip is there: "Slip" is something else of the user's
    EXPECT_EQ(c.warnings.size(), 1u);
}

}  // namespace
}  // namespace terra::io
