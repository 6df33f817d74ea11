#include "scene/tokenizer.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace penumbra {

namespace {

bool isSeparator(char c) {
  // '\r' counts as a separator so that files with Windows line endings read the same.
  return c == ' ' || c == '\t' || c == '\r';
}

SourceLocation locationAt(const std::string& file, int line, std::size_t index) {
  return SourceLocation{file, line, static_cast<int>(index) + 1};
}

TokenLine tokenizeLine(std::string_view text, int lineNumber, const std::string& file) {
  TokenLine result;
  result.line = lineNumber;
  std::size_t index = 0;
  while (index < text.size()) {
    const char c = text[index];
    if (isSeparator(c)) {
      ++index;
      continue;
    }
    if (c == '#')
      break;

    Token token;
    token.where = locationAt(file, lineNumber, index);
    if (c == '"') {
      const std::size_t closing = text.find('"', index + 1);
      if (closing == std::string_view::npos)
        throw SceneError(token.where, "unterminated quoted string: expected a closing '\"'");
      token.text = std::string(text.substr(index + 1, closing - index - 1));
      token.quoted = true;
      index = closing + 1;
      // Text glued to the closing quote would silently join the next token otherwise.
      if (index < text.size() && !isSeparator(text[index]) && text[index] != '#')
        throw SceneError(locationAt(file, lineNumber, index),
                         "expected a space after the closing '\"'");
    } else {
      std::size_t end = index;
      while (end < text.size() && !isSeparator(text[end]) && text[end] != '#') {
        if (text[end] == '"')
          throw SceneError(locationAt(file, lineNumber, end),
                           "unexpected '\"' inside a word: quote the whole path");
        ++end;
      }
      token.text = std::string(text.substr(index, end - index));
      index = end;
    }
    result.tokens.push_back(std::move(token));
  }
  return result;
}

}  // namespace

std::vector<TokenLine> tokenize(std::string_view text, const std::string& file) {
  // Some editors start UTF-8 files with a byte order mark; it is not part of the first keyword.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.starts_with(kByteOrderMark))
    text.remove_prefix(kByteOrderMark.size());
  std::vector<TokenLine> lines;
  int lineNumber = 1;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos)
      end = text.size();
    TokenLine line = tokenizeLine(text.substr(start, end - start), lineNumber, file);
    if (!line.tokens.empty())
      lines.push_back(std::move(line));
    start = end + 1;
    ++lineNumber;
  }
  return lines;
}

std::string quotePath(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

std::string quoteToken(std::string_view text) {
  constexpr std::size_t kLongestQuoted = 40;
  if (text.size() <= kLongestQuoted)
    return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kLongestQuoted)) + "...' (" +
         std::to_string(text.size()) + " characters)";
}

std::string expectedFiniteNumber(std::string_view text) {
  return "expected a finite number, found " + quoteToken(text);
}

std::string expectedPositiveInteger(std::string_view text) {
  return "expected a positive integer, found " + quoteToken(text);
}

float parseNumber(const Token& token) {
  const auto fail = [&token]() {
    return SceneError(token.where, expectedFiniteNumber(token.text));
  };
  std::string_view text = token.text;
  // std::from_chars rejects a leading '+', which is still a plain decimal number.
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+')
    text.remove_prefix(1);
  // Parsed as double so that values beyond the float range are told apart from tiny ones,
  // which simply round towards zero.
  double value = 0.0;
  const auto [end, error] =
      std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
      std::abs(value) > static_cast<double>(std::numeric_limits<float>::max()))
    throw fail();
  return static_cast<float>(value);
}

}  // namespace penumbra
