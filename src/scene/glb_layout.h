#pragma once
// The chunk layout of a GLB file (binary glTF 2.0, section 4.4 of the specification), checked
// before anything reads a chunk: assimp 5.2 allocates the JSON chunk's declared length before
// reading it, so a 131-byte file declaring a 1.9 GB chunk took 2.3 GB (found by the model
// fuzzer). Used by loadModel and by the glTF scene import alike. No GL, no assimp.

#include <cstdint>
#include <istream>
#include <optional>
#include <string>

namespace penumbra {

struct GlbLayout {
  // Where the JSON chunk's content lies in the file (valid when `problem` is empty).
  std::uint64_t jsonOffset = 0;
  std::uint64_t jsonLength = 0;
  // What is wrong with the layout, e.g. "the GLB header gives its length as 644 bytes, but the
  // file has 131 (is the file truncated?)"; empty when every chunk lies within the file.
  std::string problem;
};

// nullopt when `file` (of `fileBytes` bytes, read from its start) does not begin with the GLB
// magic "glTF"; otherwise its layout, or the problem with it.
std::optional<GlbLayout> readGlbLayout(std::istream& file, std::uint64_t fileBytes);

}  // namespace penumbra
