#include "render/debug_views_shadows.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdint>

#include "render/debug_views.h"
#include "shared.h"

namespace penumbra {
namespace {

constexpr const char* kVoxelsPrefix = "voxels-";

template <class Value>
std::vector<Value> readBuffer(GLuint buffer, std::size_t count) {
  std::vector<Value> values(count);
  glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(count * sizeof(Value)), values.data());
  return values;
}

// An R32UI texture of a pyramid level, in GL order (row 0 at the bottom).
std::vector<std::uint32_t> readLevel(GLuint texture, glm::ivec2 size) {
  std::vector<std::uint32_t> values(static_cast<std::size_t>(size.x) * size.y);
  glGetTextureImage(texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                    static_cast<GLsizei>(values.size() * sizeof(std::uint32_t)), values.data());
  return values;
}

std::size_t indexOf(glm::ivec2 texel, glm::ivec2 size) {
  return static_cast<std::size_t>(texel.y) * size.x + texel.x;
}

// An image of the renderer's size whose pixel (x, y), y counted from the bottom as GL does,
// gets colour(x, y).
template <class Colour>
Image fullResolution(const Renderer& renderer, Colour colour) {
  const glm::ivec2 size = renderer.gbuffer().size;
  Image image(size.x, size.y);
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x)
      image.at(x, size.y - 1 - y) = glm::vec4(colour(glm::ivec2(x, y)), 1.0f);
  return image;
}

Image voxelSlice(const Renderer& renderer, const std::string& name) {
  const VoxelGrid& grid = renderer.voxelGrid();
  if (grid.wordCount == 0)
    throw RenderError("debug view '" + name +
                      "' needs a frame with voxel shadows (not --no-shadows or --visibility bvh)");
  const std::string sliceText = name.substr(std::string(kVoxelsPrefix).size());
  const glm::ivec4 resolution = grid.description.resolution;
  int slice = -1;
  if (!sliceText.empty() && sliceText.size() < 6 &&
      std::all_of(sliceText.begin(), sliceText.end(), [](char c) { return std::isdigit(c); }))
    slice = std::stoi(sliceText);
  if (slice < 0 || slice >= resolution.z) {
    throw RenderError("debug view '" + name + "': the voxel grid's slices are 0 to " +
                      std::to_string(resolution.z - 1));
  }
  // The columns along z come first in the words (voxel_grid.glsl).
  const std::vector<std::uint32_t> words = readBuffer<std::uint32_t>(
      grid.words.id(), static_cast<std::size_t>(resolution.x) * resolution.y * resolution.w);
  const glm::ivec2 size = renderer.gbuffer().size;
  return fullResolution(renderer, [&](glm::ivec2 pixel) {
    const glm::ivec2 column = pixel * glm::ivec2(resolution) / size;
    const std::uint32_t word =
        words[indexOf(column, {resolution.x, resolution.y}) * resolution.w + slice / 32];
    return (word >> (slice % 32) & 1u) != 0u ? glm::vec3(1.0f) : glm::vec3(0.12f);
  });
}

const Pyramid& requireMasks(const Renderer& renderer, const VisibilityMasks* masks,
                            const std::string& name) {
  if (renderer.pyramid() == nullptr || masks == nullptr)
    throw RenderError("debug view '" + name + "' needs a hierarchical frame with shadows");
  return *renderer.pyramid();
}

// Per level, in GL order.
std::vector<std::vector<std::uint32_t>> readLevels(const Pyramid& pyramid,
                                                   GLuint (Pyramid::*texture)(int) const) {
  std::vector<std::vector<std::uint32_t>> levels;
  for (int level = 0; level < pyramid.levelCount(); ++level)
    levels.push_back(readLevel((pyramid.*texture)(level), pyramid.size(level)));
  return levels;
}

Image visibleVpls(const Renderer& renderer, const VisibilityMasks& masks, const Pyramid& pyramid) {
  const std::vector<std::vector<std::uint32_t>> states = readLevels(pyramid, &Pyramid::state);
  const int coarsest = pyramid.levelCount() - 1;
  const std::size_t maskWords =
      masks.maskOffset(coarsest) + static_cast<std::size_t>(pyramid.size(coarsest).x) *
                                       pyramid.size(coarsest).y * masks.wordsPerMask();
  const std::vector<std::uint32_t> words = readBuffer<std::uint32_t>(masks.masks(), maskWords);
  return fullResolution(renderer, [&](glm::ivec2 pixel) {
    // The mask of the texel the pixel's light was gathered at.
    for (int level = coarsest; level >= 0; --level) {
      const glm::ivec2 texel = pixel >> level;
      const glm::ivec2 size = pyramid.size(level);
      if (states[static_cast<std::size_t>(level)][indexOf(texel, size)] != gpu::kTexelComputed)
        continue;
      const std::size_t first =
          masks.maskOffset(level) + indexOf(texel, size) * masks.wordsPerMask();
      int visible = 0;
      for (int word = 0; word < masks.wordsPerMask(); ++word)
        visible += std::popcount(words[first + static_cast<std::size_t>(word)]);
      return colourMap(static_cast<float>(visible) / static_cast<float>(masks.vplCount()));
    }
    return glm::vec3(0.0f);
  });
}

Image visibilityRefinement(const Renderer& renderer, const Pyramid& pyramid) {
  const std::vector<std::vector<std::uint32_t>> flags =
      readLevels(pyramid, &Pyramid::visibilityFlags);
  return fullResolution(renderer, [&](glm::ivec2 pixel) {
    glm::vec3 colour(0.0f);
    for (int level = pyramid.levelCount() - 1; level >= 0; --level) {
      const std::uint32_t flag =
          flags[static_cast<std::size_t>(level)][indexOf(pixel >> level, pyramid.size(level))];
      if ((flag & gpu::kVisibilityChanges) != 0u)
        colour = levelColour(level);
      else if ((flag & gpu::kVisibilityHasMask) != 0u && colour == glm::vec3(0.0f))
        colour = glm::vec3(0.35f);
    }
    return colour;
  });
}

}  // namespace

std::vector<std::string> shadowDebugViewNames(const Renderer& renderer,
                                              const VisibilityMasks* masks) {
  std::vector<std::string> names;
  if (renderer.voxelGrid().wordCount > 0)
    names.push_back("voxels-N");
  if (renderer.pyramid() != nullptr && masks != nullptr)
    names.insert(names.end(), {"visible-vpls", "visibility-refinement"});
  return names;
}

std::optional<Image> shadowDebugView(const Renderer& renderer, const VisibilityMasks* masks,
                                     const std::string& name) {
  if (name.starts_with(kVoxelsPrefix))
    return voxelSlice(renderer, name);
  if (name == "visible-vpls") {
    const Pyramid& pyramid = requireMasks(renderer, masks, name);
    return visibleVpls(renderer, *masks, pyramid);
  }
  if (name == "visibility-refinement")
    return visibilityRefinement(renderer, requireMasks(renderer, masks, name));
  return std::nullopt;
}

}  // namespace penumbra
