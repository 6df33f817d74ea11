#include "render/debug_view_registry.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "render/levels.h"
#include "render/readback.h"

namespace penumbra {

glm::vec3 colourMap(float t) {
  static constexpr std::array<glm::vec3, 5> stops = {
      glm::vec3(0.05f, 0.03f, 0.35f), glm::vec3(0.40f, 0.05f, 0.55f),
      glm::vec3(0.80f, 0.25f, 0.35f), glm::vec3(0.97f, 0.60f, 0.15f),
      glm::vec3(0.98f, 0.98f, 0.45f)};
  const float position = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(stops.size() - 1);
  const auto index = std::min(static_cast<std::size_t>(position), stops.size() - 2);
  return glm::mix(stops[index], stops[index + 1], position - static_cast<float>(index));
}

glm::vec3 texelStateColour(std::uint32_t state) {
  switch (state) {
    case gpu::kTexelComputed:
      return glm::vec3(1.0f);
    case gpu::kTexelCovered:
      return glm::vec3(0.35f);
    case gpu::kTexelRefined:
      return glm::vec3(0.85f, 0.15f, 0.1f);
    case gpu::kTexelUnlit:
      return glm::vec3(0.1f, 0.2f, 0.6f);
    default:
      return glm::vec3(0.0f);
  }
}

glm::vec3 levelColour(int level) {
  static constexpr std::array<glm::vec3, 8> colours = {
      glm::vec3(0.90f, 0.10f, 0.10f), glm::vec3(0.95f, 0.55f, 0.10f),
      glm::vec3(0.95f, 0.90f, 0.15f), glm::vec3(0.25f, 0.80f, 0.25f),
      glm::vec3(0.15f, 0.75f, 0.85f), glm::vec3(0.20f, 0.35f, 0.90f),
      glm::vec3(0.60f, 0.25f, 0.85f), glm::vec3(0.90f, 0.40f, 0.75f)};
  return colours[static_cast<std::size_t>(level) % colours.size()];
}

namespace {

DebugViewSource fromTexture(GLuint texture, glm::ivec2 size, int kind) {
  DebugViewSource view;
  view.texture = texture;
  view.size = size;
  view.kind = kind;
  return view;
}

DebugViewSource scalar(GLuint texture, glm::ivec2 size, int channel, std::string quantity) {
  DebugViewSource view = fromTexture(texture, size, gpu::kDisplayScalar);
  view.channel = channel;
  view.quantity = std::move(quantity);
  return view;
}

// A distance to the eye in channel w, zero on the background, over the picture's own range.
DebugViewSource depth(GLuint texture, glm::ivec2 size) {
  DebugViewSource view = scalar(texture, size, 3, "distance to the eye");
  view.fitRange = true;
  view.maskChannel = 3;
  return view;
}

// Threshold exceedance: the threshold sits in the middle of the map, and texels that are not
// lit surfaces (b = 1) are black.
DebugViewSource discontinuity(const HierarchyTargets& hierarchy, int level, int channel,
                              float threshold, const char* quantity) {
  DebugViewSource view =
      scalar(hierarchy.reduced.discontinuity(level).id(), hierarchy.layout.size(level), channel,
             std::string(quantity) + "; threshold " + std::to_string(threshold) + " in the middle");
  view.range = {0.0f, 2.0f * threshold};
  view.maskChannel = 2;
  view.maskValue = 1.0f;
  return view;
}

DebugViewSource categories(GLuint texture, glm::ivec2 size, bool unsignedTexture, int channel,
                           std::vector<LegendEntry> palette) {
  DebugViewSource view = fromTexture(texture, size, gpu::kDisplayCategories);
  view.unsignedTexture = unsignedTexture;
  view.channel = channel;
  view.palette = std::move(palette);
  return view;
}

std::vector<LegendEntry> texelStatePalette() {
  std::vector<LegendEntry> palette;
  const std::pair<std::uint32_t, const char*> states[] = {
      {gpu::kTexelInvalid, "invalid: background, light, outside"},
      {gpu::kTexelComputed, "computed at this level"},
      {gpu::kTexelCovered, "covered: upsampled from a coarser level"},
      {gpu::kTexelRefined, "refined: finer levels compute it"},
      {gpu::kTexelUnlit, "unlit: faces away from every light"}};
  for (const auto& [state, label] : states)
    palette.push_back({texelStateColour(state), label});
  return palette;
}

std::string levelLabel(const LevelLayout& layout, int level) {
  const glm::ivec2 size = layout.size(level);
  return "level " + std::to_string(level) + " (" + std::to_string(size.x) + "x" +
         std::to_string(size.y) + ")";
}

std::vector<LegendEntry> levelPalette(const LevelLayout& layout) {
  std::vector<LegendEntry> palette;
  for (int level = 0; level < layout.levelCount(); ++level)
    palette.push_back({levelColour(level), levelLabel(layout, level) + "; darker: unlit"});
  return palette;
}

// --- views gathered on the CPU from the passes' buffers ---------------------------------------

// An R32UI texture per level, in GL order (row 0 at the bottom).
template <class LevelTexture>
std::vector<std::vector<std::uint32_t>> readLevels(const LevelLayout& layout,
                                                   LevelTexture texture) {
  std::vector<std::vector<std::uint32_t>> levels;
  for (int level = 0; level < layout.levelCount(); ++level)
    levels.push_back(
        readUintTexture(texture(level).id(), layout.size(level), RowOrder::BottomFirst));
  return levels;
}

std::size_t indexOf(glm::ivec2 texel, glm::ivec2 size) {
  return static_cast<std::size_t>(texel.y) * size.x + texel.x;
}

// An RGBA32F texture of the renderer's size whose texel (x, y), in GL order, is value(x, y).
template <class Value>
std::shared_ptr<const gl::Texture> fullResolution(const Renderer& renderer, Value value) {
  const glm::ivec2 size = renderer.gbuffer().size;
  std::vector<glm::vec4> texels(static_cast<std::size_t>(size.x) * size.y);
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x)
      texels[indexOf({x, y}, size)] = value(glm::ivec2(x, y));
  auto texture = std::make_shared<gl::Texture>(GL_TEXTURE_2D);
  glTextureStorage2D(texture->id(), 1, GL_RGBA32F, size.x, size.y);
  glTextureSubImage2D(texture->id(), 0, 0, 0, size.x, size.y, GL_RGBA, GL_FLOAT, texels.data());
  return texture;
}

DebugViewSource gathered(const Renderer& renderer, std::shared_ptr<const gl::Texture> texture,
                         int kind) {
  DebugViewSource view = fromTexture(texture->id(), renderer.gbuffer().size, kind);
  view.ownedTexture = std::move(texture);
  return view;
}

// Slice `slice` along z of the voxel grid (world grid: the slab at z index N, x to the right,
// y up; screen grid: depth slice N as the camera sees it), stretched over the image: x is 1
// where a voxel is occupied.
DebugViewSource voxelSlice(const Renderer& renderer, int slice) {
  const VoxelGrid& grid = renderer.voxelGrid();
  const glm::ivec4 resolution = grid.description.resolution;
  // The columns along z come first in the words (voxel_grid.glsl).
  const std::vector<std::uint32_t> words = readBuffer<std::uint32_t>(
      grid.words.id(), 0, static_cast<std::size_t>(resolution.x) * resolution.y * resolution.w);
  const glm::ivec2 size = renderer.gbuffer().size;
  DebugViewSource view = gathered(
      renderer,
      fullResolution(renderer,
                     [&](glm::ivec2 pixel) {
                       const glm::ivec2 column = pixel * glm::ivec2(resolution) / size;
                       const std::uint32_t word =
                           words[indexOf(column, {resolution.x, resolution.y}) * resolution.w +
                                 static_cast<std::size_t>(slice / 32)];
                       return glm::vec4((word >> (slice % 32) & 1u) != 0u ? 1.0f : 0.0f);
                     }),
      gpu::kDisplayCategories);
  view.palette = {{glm::vec3(0.12f), "empty"}, {glm::vec3(1.0f), "occupied"}};
  return view;
}

// Per pixel, the share of the VPLs its visibility mask leaves unoccluded, from the level the
// pixel was gathered at (x); y is 1 where the pixel has such a mask.
DebugViewSource visibleVpls(const Renderer& renderer) {
  const VisibilityMasks& masks = *renderer.visibilityMasks();
  const HierarchyTargets& hierarchy = *renderer.hierarchy();
  const LevelLayout& layout = hierarchy.layout;
  const std::vector<std::vector<std::uint32_t>> states = readLevels(
      layout, [&](int level) -> const gl::Texture& { return hierarchy.refinement.state(level); });
  const int coarsest = layout.coarsest();
  const std::size_t maskWords =
      masks.maskOffset(coarsest) + static_cast<std::size_t>(layout.size(coarsest).x) *
                                       layout.size(coarsest).y * masks.wordsPerMask();
  const std::vector<std::uint32_t> words =
      readBuffer<std::uint32_t>(masks.masks().id(), 0, maskWords);
  DebugViewSource view = gathered(
      renderer,
      fullResolution(renderer,
                     [&](glm::ivec2 pixel) {
                       for (int level = coarsest; level >= 0; --level) {
                         const glm::ivec2 texel = pixel >> level;
                         const glm::ivec2 size = layout.size(level);
                         if (states[static_cast<std::size_t>(level)][indexOf(texel, size)] !=
                             gpu::kTexelComputed)
                           continue;
                         const std::size_t first =
                             masks.maskOffset(level) + indexOf(texel, size) * masks.wordsPerMask();
                         int visible = 0;
                         for (int word = 0; word < masks.wordsPerMask(); ++word)
                           visible += std::popcount(words[first + static_cast<std::size_t>(word)]);
                         return glm::vec4(
                             static_cast<float>(visible) / static_cast<float>(masks.vplCount()),
                             1.0f, 0.0f, 0.0f);
                       }
                       return glm::vec4(0.0f);
                     }),
      gpu::kDisplayScalar);
  view.quantity = "share of the " + std::to_string(masks.vplCount()) + " VPLs visible";
  view.maskChannel = 1;
  return view;
}

// Per pixel, the finest level at which its visibility differed from a neighbour's: x is
// 2 + that level, 1 where a mask was traced and never differed, 0 where there is none.
DebugViewSource visibilityRefinement(const Renderer& renderer) {
  const HierarchyTargets& hierarchy = *renderer.hierarchy();
  const LevelLayout& layout = hierarchy.layout;
  const std::vector<std::vector<std::uint32_t>> flags = readLevels(
      layout, [&](int level) -> const gl::Texture& { return hierarchy.visibility.flags(level); });
  DebugViewSource view = gathered(
      renderer,
      fullResolution(renderer,
                     [&](glm::ivec2 pixel) {
                       float category = 0.0f;
                       for (int level = layout.coarsest(); level >= 0; --level) {
                         const std::uint32_t flag = flags[static_cast<std::size_t>(level)][indexOf(
                             pixel >> level, layout.size(level))];
                         if ((flag & gpu::kVisibilityChanges) != 0u)
                           category = 2.0f + static_cast<float>(level);
                         else if ((flag & gpu::kVisibilityHasMask) != 0u && category == 0.0f)
                           category = 1.0f;
                       }
                       return glm::vec4(category);
                     }),
      gpu::kDisplayCategories);
  view.palette = {{glm::vec3(0.0f), "no mask"}, {glm::vec3(0.35f), "mask traced, never differed"}};
  for (int level = 0; level < layout.levelCount(); ++level)
    view.palette.push_back({levelColour(level), "differs at " + levelLabel(layout, level)});
  return view;
}

}  // namespace

const std::vector<DebugViewInfo>& debugViewInfos() {
  using enum DebugViewNeeds;
  static const std::vector<DebugViewInfo> infos = {
      {"radiance", "final linear radiance", false, 0, AnyFrame},
      {"albedo", "G-buffer: diffuse albedo", false, 0, AnyFrame},
      {"normal", "G-buffer: normal facing the eye (0.5 N + 0.5)", false, 0, AnyFrame},
      {"depth", "G-buffer: distance to the eye", false, 0, AnyFrame},
      {"pixel-kind", "G-buffer: background, surface or light", false, 0, AnyFrame},
      {"specular", "G-buffer: specular colour k_s", false, 0, AnyFrame},
      {"shininess", "G-buffer: Phong exponent", false, 0, AnyFrame},
      {"emission", "G-buffer: emission of lights, ambient of surfaces", false, 0, AnyFrame},
      {"indirect", "indirect light alone (one bounce; black when off)", false, 0, AnyFrame},
      {"indirect-exact", "indirect light: pixels gathered exactly, not upsampled", false, 0,
       AnyFrame},
      {"levels", "level each pixel's lighting came from", false, 0, HierarchicalResults},
      {"worklist", "what the refinement decided per texel", true, 0, Hierarchical},
      {"depth-discontinuity", "relative depth gradient", true, 0, Hierarchical},
      {"normal-discontinuity", "normal change between neighbours", true, 0, Hierarchical},
      {"light-proximity", "extent over the distance to the nearest light", true, 0, Hierarchical},
      {"visibility-flags", "visibility masks and where they differ", true, 0, Hierarchical},
      {"level-depth", "pyramid: mean distance to the eye", true, 0, Hierarchical},
      {"level-normal", "pyramid: mean normal", true, 0, Hierarchical},
      {"coverage", "pyramid: fraction of the footprint that is lit surface", true, 1, Hierarchical},
      {"diffuse-result", "pyramid: diffuse gather result", true, 0, HierarchicalResults},
      {"specular-result", "pyramid: specular gather result", true, 0, HierarchicalResults},
      {"voxels", "voxel grid: occupied voxels of one slice along z", true, 0, Shadows},
      {"visible-vpls", "share of the VPLs each pixel's visibility mask sees", false, 0,
       HierarchicalShadows},
      {"visibility-refinement", "finest level where a pixel's visibility differed", false, 0,
       HierarchicalShadows}};
  return infos;
}

const DebugViewInfo* findDebugView(const std::string& name) {
  for (const DebugViewInfo& info : debugViewInfos())
    if (name == info.name)
      return &info;
  return nullptr;
}

std::string debugViewNameList() {
  std::string names;
  for (const DebugViewInfo& info : debugViewInfos())
    names += (names.empty() ? "" : ", ") + std::string(info.name) + (info.indexed ? "[-N]" : "");
  return names;
}

bool debugViewAvailable(const DebugViewInfo& info, const Renderer& renderer, std::string* why) {
  const bool hierarchical = renderer.hierarchy() != nullptr;
  const bool voxels = renderer.voxelGrid().wordCount > 0;
  const char* missing = nullptr;
  switch (info.needs) {
    case DebugViewNeeds::AnyFrame:
      break;
    case DebugViewNeeds::Hierarchical:
      if (!hierarchical || renderer.hierarchy()->layout.levelCount() <= info.firstIndex)
        missing = "the hierarchical mode";
      break;
    case DebugViewNeeds::HierarchicalResults:
      if (!renderer.canCompleteGatheredLevels())
        missing = "a hierarchical last frame";
      break;
    case DebugViewNeeds::Shadows:
      if (!voxels)
        missing = "a frame with voxel shadows (not --no-shadows or --visibility bvh)";
      break;
    case DebugViewNeeds::HierarchicalShadows:
      if (!hierarchical || renderer.visibilityMasks() == nullptr)
        missing = "a hierarchical frame with shadows";
      break;
  }
  if (missing != nullptr && why != nullptr)
    *why = "debug view '" + std::string(info.name) + "' needs " + missing;
  return missing == nullptr;
}

glm::ivec2 debugViewIndices(const DebugViewInfo& info, const Renderer& renderer) {
  if (!info.indexed)
    return {0, 0};
  if (info.needs == DebugViewNeeds::Shadows)
    return {0, renderer.voxelGrid().description.resolution.z - 1};
  return {info.firstIndex, renderer.hierarchy()->layout.coarsest()};
}

DebugViewSource debugViewSource(const DebugViewInfo& info, int index, const Renderer& renderer,
                                const RenderSettings& settings) {
  const GBuffer& gbuffer = renderer.gbuffer();
  const std::string name = info.name;
  const glm::ivec2 indices = debugViewIndices(info, renderer);
  index = std::clamp(index, indices.x, indices.y);
  if (name == "radiance")
    return fromTexture(renderer.radiance().id(), gbuffer.size, gpu::kDisplayRadiance);
  if (name == "albedo")
    return fromTexture(gbuffer.albedo.id(), gbuffer.size, gpu::kDisplayColour);
  if (name == "normal")
    return fromTexture(gbuffer.normalKind.id(), gbuffer.size, gpu::kDisplayNormal);
  if (name == "depth")
    return depth(gbuffer.positionDepth.id(), gbuffer.size);
  if (name == "pixel-kind") {
    return categories(gbuffer.normalKind.id(), gbuffer.size, false, 3,
                      {{glm::vec3(0.0f), "background"},
                       {glm::vec3(0.5f), "surface"},
                       {glm::vec3(0.95f, 0.8f, 0.2f), "light"}});
  }
  if (name == "specular")
    return fromTexture(gbuffer.specular.id(), gbuffer.size, gpu::kDisplayColour);
  if (name == "shininess") {
    DebugViewSource view = scalar(gbuffer.specular.id(), gbuffer.size, 3, "Phong exponent");
    view.fitRange = true;
    return view;
  }
  if (name == "emission")
    return fromTexture(gbuffer.emission.id(), gbuffer.size, gpu::kDisplayRadiance);
  if (name == "indirect")
    return fromTexture(renderer.indirect().id(), gbuffer.size, gpu::kDisplayRadiance);
  if (name == "indirect-exact")
    return scalar(renderer.indirect().id(), gbuffer.size, 3, "1: gathered exactly");
  if (name == "voxels")
    return voxelSlice(renderer, index);
  if (name == "visible-vpls")
    return visibleVpls(renderer);
  if (name == "visibility-refinement")
    return visibilityRefinement(renderer);

  const HierarchyTargets& hierarchy = *renderer.hierarchy();
  const ReducedGBuffer& reduced = hierarchy.reduced;
  const glm::ivec2 size = hierarchy.layout.size(index);
  const MultiresolutionSettings& multiresolution = settings.multiresolution;
  if (name == "levels") {
    DebugViewSource view = fromTexture(renderer.completedGatheredLevels().diffuse(0).id(),
                                       gbuffer.size, gpu::kDisplayLevels);
    view.palette = levelPalette(hierarchy.layout);
    return view;
  }
  if (name == "worklist")
    return categories(hierarchy.refinement.state(index).id(), size, true, 0, texelStatePalette());
  if (name == "depth-discontinuity") {
    return discontinuity(hierarchy, index, 0, multiresolution.depthThreshold,
                         "|grad z| / z times the image size");
  }
  if (name == "normal-discontinuity")
    return discontinuity(hierarchy, index, 1, multiresolution.normalThreshold, "|N1 - N2|");
  if (name == "light-proximity") {
    // Level N refines where 2^N times the pixels' proximity exceeds the threshold.
    return discontinuity(hierarchy, index, 3,
                         multiresolution.lightProximityThreshold / static_cast<float>(1 << index),
                         "pixel extent / distance to the nearest light");
  }
  if (name == "visibility-flags") {
    return categories(hierarchy.visibility.flags(index).id(), size, true, 0,
                      {{glm::vec3(0.0f), "no mask"},
                       {glm::vec3(0.5f), "mask traced or inherited"},
                       {glm::vec3(0.95f, 0.55f, 0.1f), "visibility changes, no mask"},
                       {glm::vec3(0.9f, 0.1f, 0.1f), "mask differs from a neighbour's"},
                       {glm::vec3(0.2f, 0.35f, 0.9f), "faces no light: no mask"}});
  }
  if (name == "level-depth")
    return depth(reduced.positionDepth(index).id(), size);
  if (name == "level-normal")
    return fromTexture(reduced.normal(index).id(), size, gpu::kDisplayNormal);
  if (name == "coverage")
    return scalar(reduced.normal(index).id(), size, 3, "fraction of lit surface");
  if (name == "diffuse-result")
    return fromTexture(renderer.completedGatheredLevels().diffuse(index).id(), size,
                       gpu::kDisplayRadiance);
  if (name == "specular-result")
    return fromTexture(renderer.completedGatheredLevels().specular(index).id(), size,
                       gpu::kDisplayRadiance);
  throw std::logic_error("debug view '" + name + "' has no source");
}

glm::vec2 valueRange(const DebugViewSource& view) {
  const Image image = readTexture(view.texture, view.size, RowOrder::TopFirst);
  glm::vec2 range(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
  for (const glm::vec4& pixel : image.pixels) {
    if (view.maskChannel >= 0 && pixel[view.maskChannel] == view.maskValue)
      continue;
    range.x = std::min(range.x, pixel[view.channel]);
    range.y = std::max(range.y, pixel[view.channel]);
  }
  return range.x <= range.y ? range : glm::vec2(0.0f, 1.0f);
}

}  // namespace penumbra
