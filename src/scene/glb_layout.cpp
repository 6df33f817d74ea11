#include "scene/glb_layout.h"

#include <array>

namespace penumbra {

namespace {

// "glTF" and "JSON", little endian.
constexpr std::uint32_t kMagic = 0x46546C67;
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;
constexpr std::uint32_t kVersion = 2;
constexpr std::uint64_t kHeaderBytes = 12;
constexpr std::uint64_t kChunkHeaderBytes = 8;

// The little-endian words of `count` x 4 bytes at `offset`; nullopt when the file ends first.
template <std::size_t count>
std::optional<std::array<std::uint32_t, count>> readWords(std::istream& file,
                                                          std::uint64_t offset) {
  std::array<unsigned char, 4 * count> bytes{};
  file.clear();
  file.seekg(static_cast<std::streamoff>(offset));
  file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (file.gcount() != static_cast<std::streamsize>(bytes.size()))
    return std::nullopt;
  std::array<std::uint32_t, count> words{};
  for (std::size_t w = 0; w < count; ++w)
    for (int b = 3; b >= 0; --b)
      words[w] = (words[w] << 8) | bytes[4 * w + static_cast<std::size_t>(b)];
  return words;
}

}  // namespace

std::optional<GlbLayout> readGlbLayout(std::istream& file, std::uint64_t fileBytes) {
  const std::optional<std::array<std::uint32_t, 1>> magic = readWords<1>(file, 0);
  if (!magic || (*magic)[0] != kMagic)
    return std::nullopt;
  GlbLayout layout;
  const std::optional<std::array<std::uint32_t, 5>> start = readWords<5>(file, 0);
  if (!start || fileBytes < kHeaderBytes + kChunkHeaderBytes) {
    layout.problem = "the GLB header is cut short";
    return layout;
  }
  const std::uint32_t version = (*start)[1];
  const std::uint32_t length = (*start)[2];
  const std::uint32_t jsonLength = (*start)[3];
  const std::uint32_t jsonType = (*start)[4];
  if (version != kVersion) {
    layout.problem = "the GLB is of version " + std::to_string(version) +
                     "; only glTF 2.0's GLB (version 2) is read";
    return layout;
  }
  if (length > fileBytes) {
    layout.problem = "the GLB header gives its length as " + std::to_string(length) +
                     " bytes, but the file has " + std::to_string(fileBytes) +
                     " (is the file truncated?)";
    return layout;
  }
  if (jsonType != kJsonChunk || jsonLength > length - kHeaderBytes - kChunkHeaderBytes) {
    layout.problem = "the GLB's first chunk is not a JSON chunk within the file";
    return layout;
  }
  layout.jsonOffset = kHeaderBytes + kChunkHeaderBytes;
  layout.jsonLength = jsonLength;
  // The chunks after the JSON (a binary buffer, extensions' own) must lie within the length too.
  std::uint64_t next = layout.jsonOffset + jsonLength;
  for (int chunk = 1; next + kChunkHeaderBytes <= length; ++chunk) {
    const std::optional<std::array<std::uint32_t, 2>> header = readWords<2>(file, next);
    const std::uint64_t end = next + kChunkHeaderBytes + (header ? (*header)[0] : 0);
    if (!header || end > length) {
      layout.problem = "the GLB's chunk " + std::to_string(chunk) + " (at byte " +
                       std::to_string(next) + ") ends at byte " + std::to_string(end) +
                       ", past the GLB's length of " + std::to_string(length) +
                       " bytes (is the file truncated?)";
      return layout;
    }
    next = end;
  }
  return layout;
}

}  // namespace penumbra
