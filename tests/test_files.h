#pragma once
// Helpers for tests that write small input files of their own.

#include <filesystem>
#include <string>
#include <string_view>

namespace penumbra::test {

// A fresh, empty directory for the running test, removed at the next call for the same test.
std::filesystem::path scratchDirectory();

// Writes `contents` to `directory / name` and returns the path.
std::filesystem::path writeFile(const std::filesystem::path& directory, std::string_view name,
                                std::string_view contents);

// The whole contents of `file`; throws std::runtime_error when it cannot be read.
std::string readFile(const std::filesystem::path& file);

// The repository's root (for scenes/ and tests/data/).
std::filesystem::path sourceDirectory();

}  // namespace penumbra::test
