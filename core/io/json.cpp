#include "core/io/json.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "core/common/quoted.h"
#include "core/io/atomic_file.h"

namespace terra::io {
namespace {

using nlohmann::json;

// Deeper nesting than this is no file of ours and would only exhaust the stack.
constexpr int kMaxDepth = 256;

struct Position {
    int line = 1;
    int column = 1;
};

struct SyntaxError {
    Position at;
    std::string message;
};

// A recursive-descent parser over the UTF-8 text that builds an nlohmann::json value and keeps the
// position of every token for the messages.
class Parser {
public:
    Parser(std::string_view text, std::string source, std::vector<BadNumber>* bad_numbers = nullptr)
        : text_(text), source_(std::move(source)), bad_numbers_(bad_numbers) {}

    Result<json> parse() {
        // A UTF-8 byte-order mark is not JSON but some editors write one: skip it.
        if (text_.substr(0, 3) == "\xEF\xBB\xBF") advance(3);
        try {
            skipSpace();
            json value = parseValue(0);
            skipSpace();
            if (i_ < text_.size()) fail("unexpected " + describeNext() + " after the JSON value");
            if (!issues_.empty()) return issues_;
            return value;
        } catch (const SyntaxError& e) {
            return std::vector<Issue>{{where(e.at), "invalid JSON: " + e.message}};
        }
    }

private:
    std::string where(const Position& p) const {
        const std::string at = std::to_string(p.line) + ":" + std::to_string(p.column);
        return source_.empty() ? "line " + at : source_ + ":" + at;
    }

    std::string path() const {
        std::string out;
        for (const std::string& segment : path_) {
            if (!segment.empty() && segment[0] == '[') {
                out += segment;
            } else {
                out += (out.empty() ? "" : ".") + segment;
            }
        }
        return out;
    }

    [[noreturn]] void fail(const std::string& message) const { throw SyntaxError{pos_, message}; }

    bool atEnd() const { return i_ >= text_.size(); }
    char peek() const { return text_[i_]; }

    // Moves on `count` bytes, counting characters (not UTF-8 continuation bytes) for the column.
    void advance(std::size_t count = 1) {
        for (std::size_t k = 0; k < count && i_ < text_.size(); ++k, ++i_) {
            const auto byte = static_cast<unsigned char>(text_[i_]);
            if (byte == '\n') {
                ++pos_.line;
                pos_.column = 1;
            } else if ((byte & 0xC0) != 0x80) {
                ++pos_.column;
            }
        }
    }

    void skipSpace() {
        while (!atEnd() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r'))
            advance();
    }

    std::string describeNext() const {
        if (atEnd()) return "end of input";
        const auto byte = static_cast<unsigned char>(peek());
        if (byte < 0x20 || byte >= 0x7F) {
            static const char* kHex = "0123456789ABCDEF";
            return std::string("byte 0x") + kHex[byte >> 4] + kHex[byte & 15];
        }
        return std::string("'") + peek() + "'";
    }

    void expect(char c, const char* context) {
        if (atEnd() || peek() != c) {
            fail(std::string("expected '") + c + "' " + context + ", got " + describeNext());
        }
        advance();
    }

    json parseValue(int depth) {
        if (depth > kMaxDepth) fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
        if (atEnd()) fail("expected a value, got end of input");
        switch (peek()) {
            case '{':
                return parseObject(depth);
            case '[':
                return parseArray(depth);
            case '"':
                return parseString();
            case 't':
                return parseLiteral("true", json(true));
            case 'f':
                return parseLiteral("false", json(false));
            case 'n':
                return parseLiteral("null", json(nullptr));
            default:
                if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return parseNumber();
                fail(
                    "expected a value (object, array, string, number, true, false or null), "
                    "got " +
                    describeNext());
        }
    }

    json parseLiteral(std::string_view word, json value) {
        if (text_.substr(i_, word.size()) != word) {
            fail("expected a value (object, array, string, number, true, false or null), got " +
                 describeNext());
        }
        advance(word.size());
        return value;
    }

    json parseObject(int depth) {
        json object = json::object();
        std::map<std::string, Position> seen;
        advance();  // '{'
        skipSpace();
        if (!atEnd() && peek() == '}') {
            advance();
            return object;
        }
        while (true) {
            skipSpace();
            if (atEnd() || peek() != '"') fail("expected a key (a string), got " + describeNext());
            const Position key_at = pos_;
            std::string key = parseString();
            skipSpace();
            expect(':', "after the key");
            skipSpace();
            path_.push_back(key);
            json value = parseValue(depth + 1);
            path_.pop_back();
            const auto [it, inserted] = seen.emplace(key, key_at);
            if (inserted) {
                object[key] = std::move(value);
            } else {
                // The path is user text too (a fuzzed 1,300-character parent key, 2026-12-02).
                const std::string in = path_.empty() ? "at the top level" : "in " + shorten(path());
                issues_.push_back(
                    {where(key_at), "duplicated key \"" + shorten(key) + "\" " + in +
                                        " (first at line " + std::to_string(it->second.line) +
                                        ", column " + std::to_string(it->second.column) + ")"});
            }
            skipSpace();
            if (!atEnd() && peek() == ',') {
                advance();
                continue;
            }
            expect('}', "or ',' after an object member");
            return object;
        }
    }

    json parseArray(int depth) {
        json array = json::array();
        advance();  // '['
        skipSpace();
        if (!atEnd() && peek() == ']') {
            advance();
            return array;
        }
        while (true) {
            skipSpace();
            path_.push_back("[" + std::to_string(array.size()) + "]");
            array.push_back(parseValue(depth + 1));
            path_.pop_back();
            skipSpace();
            if (!atEnd() && peek() == ',') {
                advance();
                continue;
            }
            expect(']', "or ',' after an array element");
            return array;
        }
    }

    // At most 80 bytes, cut at a UTF-8 character boundary (never inside a multi-byte sequence).
    static std::string shorten(const std::string& text) {
        if (text.size() <= 80) return text;
        std::size_t cut = 77;
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
        return text.substr(0, cut) + "...";
    }

    int hexDigit() {
        if (atEnd()) fail("unfinished \\u escape");
        const char c = peek();
        int value = -1;
        if (c >= '0' && c <= '9') value = c - '0';
        if (c >= 'a' && c <= 'f') value = c - 'a' + 10;
        if (c >= 'A' && c <= 'F') value = c - 'A' + 10;
        if (value < 0) fail("expected a hexadecimal digit in a \\u escape, got " + describeNext());
        advance();
        return value;
    }

    std::uint32_t hex4() {
        std::uint32_t value = 0;
        for (int k = 0; k < 4; ++k) value = value * 16 + static_cast<std::uint32_t>(hexDigit());
        return value;
    }

    static void appendUtf8(std::string& out, std::uint32_t cp) {
        if (cp < 0x80) {
            out += static_cast<char>(cp);
        } else if (cp < 0x800) {
            out += static_cast<char>(0xC0 | (cp >> 6));
            out += static_cast<char>(0x80 | (cp & 0x3F));
        } else if (cp < 0x10000) {
            out += static_cast<char>(0xE0 | (cp >> 12));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (cp & 0x3F));
        } else {
            out += static_cast<char>(0xF0 | (cp >> 18));
            out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (cp & 0x3F));
        }
    }

    // One raw UTF-8 character of a string (the lead byte is not ASCII): well-formed sequences
    // only (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF).
    void copyUtf8(std::string& out) {
        const auto lead = static_cast<unsigned char>(peek());
        int length = 0;
        std::uint32_t low = 0x80, high = 0xBF;  // allowed range of the second byte
        if (lead >= 0xC2 && lead <= 0xDF) {
            length = 2;
        } else if (lead >= 0xE0 && lead <= 0xEF) {
            length = 3;
            if (lead == 0xE0) low = 0xA0;
            if (lead == 0xED) high = 0x9F;
        } else if (lead >= 0xF0 && lead <= 0xF4) {
            length = 4;
            if (lead == 0xF0) low = 0x90;
            if (lead == 0xF4) high = 0x8F;
        } else {
            fail("invalid UTF-8 in a string (" + describeNext() + ")");
        }
        if (i_ + static_cast<std::size_t>(length) > text_.size())
            fail("invalid UTF-8 in a string (cut short)");
        for (int k = 1; k < length; ++k) {
            const auto byte = static_cast<unsigned char>(text_[i_ + static_cast<std::size_t>(k)]);
            const std::uint32_t lo = k == 1 ? low : 0x80, hi = k == 1 ? high : 0xBF;
            if (byte < lo || byte > hi) fail("invalid UTF-8 in a string");
        }
        out.append(text_.substr(i_, static_cast<std::size_t>(length)));
        advance(static_cast<std::size_t>(length));
    }

    std::string parseString() {
        advance();  // '"'
        std::string out;
        while (true) {
            if (atEnd()) fail("unterminated string");
            const auto c = static_cast<unsigned char>(peek());
            if (c == '"') {
                advance();
                return out;
            }
            if (c < 0x20) fail("control character " + describeNext() + " in a string (escape it)");
            if (c >= 0x80) {
                copyUtf8(out);
                continue;
            }
            if (c != '\\') {
                out += static_cast<char>(c);
                advance();
                continue;
            }
            advance();
            if (atEnd()) fail("unterminated string");
            const char e = peek();
            advance();
            switch (e) {
                case '"':
                case '\\':
                case '/':
                    out += e;
                    break;
                case 'b':
                    out += '\b';
                    break;
                case 'f':
                    out += '\f';
                    break;
                case 'n':
                    out += '\n';
                    break;
                case 'r':
                    out += '\r';
                    break;
                case 't':
                    out += '\t';
                    break;
                case 'u': {
                    std::uint32_t cp = hex4();
                    if (cp >= 0xDC00 && cp <= 0xDFFF) fail("lone low surrogate in a \\u escape");
                    if (cp >= 0xD800 && cp <= 0xDBFF) {
                        if (text_.substr(i_, 2) != "\\u")
                            fail("high surrogate not followed by a low one in a \\u escape");
                        advance(2);
                        const std::uint32_t second = hex4();
                        if (second < 0xDC00 || second > 0xDFFF)
                            fail("high surrogate not followed by a low one in a \\u escape");
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (second - 0xDC00);
                    }
                    appendUtf8(out, cp);
                    break;
                }
                default:
                    fail(std::string("invalid escape '\\") + e + "' in a string");
            }
        }
    }

    void digits(const char* what) {
        if (atEnd() || peek() < '0' || peek() > '9')
            fail(std::string("expected a digit ") + what + ", got " + describeNext());
        while (!atEnd() && peek() >= '0' && peek() <= '9') advance();
    }

    json parseNumber() {
        const Position at = pos_;
        const std::size_t start = i_;
        if (peek() == '-') advance();
        if (!atEnd() && peek() == '0') {
            advance();
            if (!atEnd() && peek() >= '0' && peek() <= '9')
                fail("a number must not start with 0 (leading zeros are not JSON)");
        } else {
            digits("in a number");
        }
        bool integral = true;
        if (!atEnd() && peek() == '.') {
            integral = false;
            advance();
            digits("after the decimal point");
        }
        if (!atEnd() && (peek() == 'e' || peek() == 'E')) {
            integral = false;
            advance();
            if (!atEnd() && (peek() == '+' || peek() == '-')) advance();
            digits("in the exponent");
        }
        const std::string_view token = text_.substr(start, i_ - start);
        const char* first = token.data();
        const char* last = first + token.size();
        if (integral) {
            std::int64_t signed_value = 0;
            if (std::from_chars(first, last, signed_value).ec == std::errc{}) return signed_value;
            std::uint64_t unsigned_value = 0;
            if (std::from_chars(first, last, unsigned_value).ec == std::errc{})
                return unsigned_value;
        }
        double value = 0.0;
        const auto [end, error] = std::from_chars(first, last, value);
        const bool zero_digits = token.find_first_of("123456789") == std::string_view::npos ||
                                 token.find_first_of("123456789") > token.find_first_of("eE");
        if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
            return numberIssue(at, token,
                               overflows(token) ? "is too large for a number (beyond ±1.8e308)"
                                                : "is too small for a number (below 2.2e-308, it "
                                                  "would read as 0)");
        }
        if (error != std::errc{} || end != last) fail("malformed number");
        if (std::fpclassify(value) == FP_SUBNORMAL || (value == 0.0 && !zero_digits)) {
            return numberIssue(
                at, token, "is too small for a number (below 2.2e-308, it would lose its digits)");
        }
        return value;
    }

    // Whether an out-of-range decimal token is too large (not too small): its decimal exponent,
    // the exponent part plus the position of the first significant digit, is positive.
    static bool overflows(std::string_view token) {
        const std::size_t e = token.find_first_of("eE");
        const std::string_view mantissa = token.substr(0, e);
        long exponent = 0;
        if (e != std::string_view::npos) {
            std::string_view part = token.substr(e + 1);
            if (!part.empty() && part[0] == '+') part.remove_prefix(1);
            if (std::from_chars(part.data(), part.data() + part.size(), exponent).ec != std::errc{})
                exponent = part.starts_with('-') ? -100000 : 100000;  // beyond long: huge anyway
        }
        const std::size_t point = mantissa.find('.');
        const std::size_t integer_end = point == std::string_view::npos ? mantissa.size() : point;
        const std::size_t first = mantissa.find_first_of("123456789");
        const long magnitude = first < integer_end ? static_cast<long>(integer_end - first)
                                                   : -static_cast<long>(first - integer_end - 1);
        return exponent + magnitude > 0;
    }

    // Returns the value that stands for the bad number in the document: 0 (the parse fails
    // anyway) or, when the numbers are marked, NaN.
    json numberIssue(const Position& at, std::string_view token, const std::string& what) {
        const std::string field = path();
        // The key path is user text too: shortened in the message (a fuzzed 1400-character key
        // was echoed whole), kept whole for the range lookup.
        Issue issue{where(at), (field.empty() ? std::string() : shorten(field) + ": ") +
                                   shorten(std::string(token)) + " " + what};
        if (bad_numbers_ == nullptr) {
            issues_.push_back(std::move(issue));
            return 0.0;
        }
        bad_numbers_->push_back({std::move(issue), field});
        return std::numeric_limits<double>::quiet_NaN();
    }

    std::string_view text_;
    std::string source_;
    std::size_t i_ = 0;
    Position pos_;
    std::vector<std::string> path_;        // keys and "[i]" of the value being parsed
    std::vector<Issue> issues_;            // duplicated keys, numbers out of range
    std::vector<BadNumber>* bad_numbers_;  // set: numbers out of range go here, marked NaN
};

}  // namespace

Result<json> parseJson(std::string_view text, const std::string& source) {
    return Parser(text, source).parse();
}

Result<json> parseJsonMarkingNumbers(std::string_view text, const std::string& source,
                                     std::vector<BadNumber>& bad_numbers) {
    return Parser(text, source, &bad_numbers).parse();
}

Result<json> readJsonFile(const std::filesystem::path& path) {
    std::string text;
    if (const auto error = readFile(path, text))
        return std::vector<Issue>{{pathLabel(path.string()), *error}};
    return parseJson(text, path.string());
}

std::string quoteJson(const json& value, std::size_t max_chars) {
    max_chars = std::max<std::size_t>(max_chars, 2);
    // Invalid UTF-8 in a value built in code must not throw here: replace it.
    const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
    std::size_t chars = 0, cut = 0;
    for (std::size_t k = 0; k < text.size(); ++k) {
        if ((static_cast<unsigned char>(text[k]) & 0xC0) == 0x80) continue;
        if (++chars > max_chars - 1 && cut == 0) cut = k;
    }
    if (chars <= max_chars) return text;
    return text.substr(0, cut) + "…";
}

}  // namespace terra::io
