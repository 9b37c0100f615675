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

}  // namespace
}  // namespace terra
