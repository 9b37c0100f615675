// quoteText(): user text in a message is cut to its first characters, never inside a UTF-8
// sequence, with its length given.
#include "core/common/quoted.h"

#include <gtest/gtest.h>

#include <string>

namespace terra {
namespace {

TEST(Quoted, ShortTextIsQuotedWhole) {
    EXPECT_EQ(quoteText("sandy-loam"), "'sandy-loam'");
    EXPECT_EQ(quoteText("Fx_N", '"'), "\"Fx_N\"");
    EXPECT_EQ(quoteText(std::string(80, 'a')), "'" + std::string(80, 'a') + "'");
}

TEST(Quoted, LongTextIsCutWithItsLength) {
    EXPECT_EQ(quoteText(std::string(81, 'a')), "'" + std::string(80, 'a') + "…' (81 characters)");
    EXPECT_EQ(quoteText(std::string(5000, 'k'), '"', 10), "\"kkkkkkkkkk…\" (5000 characters)");
}

TEST(Quoted, NeverCutsInsideAMultiByteCharacter) {
    // "é" is two bytes (0xC3 0xA9): 79 ASCII bytes then "é" straddles the 80-byte cut.
    const std::string text = std::string(79, 'a') + "é" + std::string(10, 'b');
    const std::string q = quoteText(text);
    EXPECT_EQ(q,
              "'" + std::string(79, 'a') + "…' (" + std::to_string(text.size()) + " characters)");
}

// Issue 28: a name with a line break or a terminal escape shows as what it is.
TEST(Quoted, ControlCharactersAreEscaped) {
    EXPECT_EQ(quoteText("a\nb"), "'a\\nb'");
    EXPECT_EQ(quoteText("a\x1b[2Jb\t"), "'a\\x1b[2Jb\\t'");
    EXPECT_EQ(quoteText(std::string("a\0b", 3)), "'a\\x00b'");
}

TEST(Quoted, PathTailKeepsTheFileName) {
    EXPECT_EQ(pathTail("/a/b.csv"), "/a/b.csv");
    const std::string deep = "/" + std::string(200, 'd') + "/points.csv";
    const std::string tail = pathTail(deep, 20);
    EXPECT_EQ(tail, "…" + deep.substr(deep.size() - 19));
    EXPECT_EQ(tail.substr(tail.size() - 10), "points.csv");
}

}  // namespace
}  // namespace terra
