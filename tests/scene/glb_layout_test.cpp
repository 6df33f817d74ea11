// The GLB layout check (scene/glb_layout.h): where the JSON chunk lies, and each way a header can
// declare more than the file holds.

#include "scene/glb_layout.h"

#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

std::string word(std::uint32_t value) {
  std::string bytes(4, '\0');
  for (int b = 0; b < 4; ++b)
    bytes[static_cast<std::size_t>(b)] = static_cast<char>((value >> (8 * b)) & 0xffu);
  return bytes;
}

constexpr std::uint32_t kJson = 0x4E4F534A;
constexpr std::uint32_t kBin = 0x004E4942;
const std::string kJsonText = R"({"asset":{"version":"2.0"}} )";  // 28 bytes: a multiple of 4

// A GLB of the JSON chunk and a binary chunk of `binBytes` bytes (declared `binDeclared`).
std::string glb(std::uint32_t version, std::uint32_t binBytes, std::uint32_t binDeclared) {
  const std::string chunks = word(static_cast<std::uint32_t>(kJsonText.size())) + word(kJson) +
                             kJsonText + word(binDeclared) + word(kBin) +
                             std::string(binBytes, '\0');
  return "glTF" + word(version) + word(static_cast<std::uint32_t>(12 + chunks.size())) + chunks;
}

std::optional<GlbLayout> layoutOf(const std::string& bytes) {
  std::istringstream file(bytes);
  return readGlbLayout(file, bytes.size());
}

TEST(GlbLayout, FindsTheJsonChunkOfAWellFormedFile) {
  const std::optional<GlbLayout> layout = layoutOf(glb(2, 16, 16));
  ASSERT_TRUE(layout);
  EXPECT_EQ(layout->problem, "");
  EXPECT_EQ(layout->jsonOffset, 20u);
  EXPECT_EQ(layout->jsonLength, kJsonText.size());
}

TEST(GlbLayout, IsNoneForOtherFiles) {
  EXPECT_FALSE(layoutOf(kJsonText));
  EXPECT_FALSE(layoutOf("gl"));
}

TEST(GlbLayout, NamesEachProblem) {
  EXPECT_EQ(layoutOf("glTF" + word(2))->problem, "the GLB header is cut short");
  EXPECT_EQ(layoutOf(glb(1, 16, 16))->problem,
            "the GLB is of version 1; only glTF 2.0's GLB (version 2) is read");
  // The length of the header beyond the file: a truncated file.
  const std::string whole = glb(2, 16, 16);
  EXPECT_EQ(layoutOf(whole.substr(0, whole.size() - 4))->problem,
            "the GLB header gives its length as 72 bytes, but the file has 68 (is the file "
            "truncated?)");
  // The fuzzer's file: a JSON chunk declared at 1.9 GB in a file of a few hundred bytes.
  std::string hugeJson = whole;
  hugeJson.replace(12, 4, word(0x7200023c));
  EXPECT_EQ(layoutOf(hugeJson)->problem,
            "the GLB's first chunk is not a JSON chunk within the file");
  std::string binaryFirst = whole;
  binaryFirst.replace(16, 4, word(kBin));
  EXPECT_EQ(layoutOf(binaryFirst)->problem,
            "the GLB's first chunk is not a JSON chunk within the file");
  EXPECT_EQ(layoutOf(glb(2, 16, 17))->problem,
            "the GLB's chunk 1 (at byte 48) ends at byte 73, past the GLB's length of 72 bytes "
            "(is the file truncated?)");
}

}  // namespace
}  // namespace penumbra
