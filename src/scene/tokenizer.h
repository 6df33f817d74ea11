#pragma once
// Splits scene text into lines of tokens, each token with its line and column.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_desc.h"

namespace penumbra {

struct Token {
  std::string text;  // quotes removed from a quoted token
  SourceLocation where;
  bool quoted = false;
};

// One non-empty line, comments removed.
struct TokenLine {
  std::vector<Token> tokens;
  int line = 0;
};

// Throws SceneError for an unterminated quote.
std::vector<TokenLine> tokenize(std::string_view text, const std::string& file);

// Parses a finite decimal number; throws SceneError (expectedFiniteNumber) otherwise.
float parseNumber(const Token& token);

// A token as error messages quote it: in single quotes, and cut after a few dozen characters (a
// token can be megabytes long), with its length then given.
std::string quoteToken(std::string_view text);
// A file path as error messages quote it: in single quotes and whole (a path is what the user
// must find on disk).
std::string quotePath(const std::filesystem::path& path);

// The messages of a value that is not what its key takes, quoting the value as written; scenes
// built in memory (scene_builder.h) report their values with the same words.
std::string expectedFiniteNumber(std::string_view text);
std::string expectedPositiveInteger(std::string_view text);

}  // namespace penumbra
