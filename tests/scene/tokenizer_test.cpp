#include "scene/tokenizer.h"

#include <cmath>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

std::string errorOf(std::string_view text) {
  try {
    tokenize(text, "t.scene");
  } catch (const SceneError& error) {
    return error.what();
  }
  return "no error";
}

std::string numberErrorOf(const std::string& text) {
  try {
    parseNumber(Token{text, SourceLocation{"t.scene", 3, 7}, false});
  } catch (const SceneError& error) {
    return error.what();
  }
  return "no error";
}

float number(const std::string& text) {
  return parseNumber(Token{text, {}, false});
}

TEST(Tokenizer, SplitsOnSpacesAndTabsWithOneBasedColumns) {
  const auto lines = tokenize("dif\t0.5  1 -2\n", "a.scene");
  ASSERT_EQ(lines.size(), 1u);
  const auto& tokens = lines[0].tokens;
  ASSERT_EQ(tokens.size(), 4u);
  EXPECT_EQ(tokens[0].text, "dif");
  EXPECT_EQ(tokens[1].text, "0.5");
  EXPECT_EQ(tokens[2].text, "1");
  EXPECT_EQ(tokens[3].text, "-2");
  EXPECT_EQ(tokens[0].where.column, 1);
  EXPECT_EQ(tokens[1].where.column, 5);
  EXPECT_EQ(tokens[2].where.column, 10);
  EXPECT_EQ(tokens[3].where.column, 12);
  EXPECT_EQ(tokens[3].where.file, "a.scene");
  EXPECT_EQ(tokens[3].where.line, 1);
}

TEST(Tokenizer, SkipsBlankLinesAndCommentsButKeepsLineNumbers) {
  const auto lines = tokenize("# header\n\n   \t\nmaterial red # the red one\n  end#done\n", "s");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].line, 4);
  ASSERT_EQ(lines[0].tokens.size(), 2u);
  EXPECT_EQ(lines[0].tokens[1].text, "red");
  EXPECT_EQ(lines[1].line, 5);
  ASSERT_EQ(lines[1].tokens.size(), 1u);
  EXPECT_EQ(lines[1].tokens[0].text, "end");
  EXPECT_EQ(lines[1].tokens[0].where.column, 3);
}

TEST(Tokenizer, LastLineWithoutNewlineAndWindowsLineEndings) {
  const auto lines = tokenize("a b\r\nc", "s");
  ASSERT_EQ(lines.size(), 2u);
  ASSERT_EQ(lines[0].tokens.size(), 2u);
  EXPECT_EQ(lines[0].tokens[1].text, "b");
  EXPECT_EQ(lines[1].tokens[0].text, "c");
  EXPECT_EQ(lines[1].line, 2);
}

TEST(Tokenizer, IgnoresAByteOrderMark) {
  const auto lines = tokenize("\xEF\xBB\xBFmaterial m", "s");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].tokens[0].text, "material");
  EXPECT_EQ(lines[0].tokens[0].where.column, 1);
}

TEST(Tokenizer, QuotedPathKeepsSpacesAndHash) {
  const auto lines = tokenize("tex \"my dir/a #1.png\" # comment", "s");
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(lines[0].tokens.size(), 2u);
  const Token& path = lines[0].tokens[1];
  EXPECT_EQ(path.text, "my dir/a #1.png");
  EXPECT_TRUE(path.quoted);
  EXPECT_FALSE(lines[0].tokens[0].quoted);
  EXPECT_EQ(path.where.column, 5);  // the opening quote
}

TEST(Tokenizer, UnterminatedQuoteIsAnErrorAtTheQuote) {
  EXPECT_EQ(errorOf("\ntex \"a b"),
            "t.scene:2:5: error: unterminated quoted string: expected a closing '\"'");
}

TEST(Tokenizer, TextGluedToAQuoteIsAnError) {
  EXPECT_EQ(errorOf("tex \"a b\"c"),
            "t.scene:1:10: error: expected a space after the closing '\"'");
  EXPECT_EQ(errorOf("tex ab\"c\""),
            "t.scene:1:7: error: unexpected '\"' inside a word: quote the whole path");
}

TEST(Tokenizer, ParsesDecimalNumbers) {
  EXPECT_EQ(number("1"), 1.0f);
  EXPECT_EQ(number("-0.5"), -0.5f);
  EXPECT_EQ(number("+2"), 2.0f);
  EXPECT_EQ(number("2.5e-3"), 2.5e-3f);
  EXPECT_EQ(number("1E2"), 100.0f);
}

TEST(Tokenizer, RejectsWhatIsNotAFiniteNumber) {
  EXPECT_EQ(numberErrorOf("nan"), "t.scene:3:7: error: expected a finite number, found 'nan'");
  EXPECT_EQ(numberErrorOf("inf"), "t.scene:3:7: error: expected a finite number, found 'inf'");
  EXPECT_EQ(numberErrorOf("-inf"), "t.scene:3:7: error: expected a finite number, found '-inf'");
  EXPECT_EQ(numberErrorOf("1e999"), "t.scene:3:7: error: expected a finite number, found '1e999'");
  // Finite as a double but beyond the float range, so it would become inf.
  EXPECT_EQ(numberErrorOf("1e39"), "t.scene:3:7: error: expected a finite number, found '1e39'");
  EXPECT_EQ(numberErrorOf("1.0abc"),
            "t.scene:3:7: error: expected a finite number, found '1.0abc'");
  for (const char* text : {"", "abc", "0x10", "1e", "-", "+-1", "1,5", "1..2"})
    EXPECT_NE(numberErrorOf(text).find("expected a finite number"), std::string::npos) << text;
}

}  // namespace
}  // namespace penumbra
