#include "app/viewer/display_views.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "render/debug_views.h"

namespace penumbra::app {
namespace {

DisplayView fromTexture(GLuint texture, glm::ivec2 size, int kind) {
  DisplayView view;
  view.texture = texture;
  view.size = size;
  view.kind = kind;
  return view;
}

DisplayView scalar(GLuint texture, glm::ivec2 size, int channel, std::string quantity) {
  DisplayView view = fromTexture(texture, size, gpu::kDisplayScalar);
  view.channel = channel;
  view.quantity = std::move(quantity);
  return view;
}

// A distance to the eye in channel w, zero on the background, over the picture's own range.
DisplayView depth(GLuint texture, glm::ivec2 size) {
  DisplayView view = scalar(texture, size, 3, "distance to the eye");
  view.fitRange = true;
  view.maskChannel = 3;
  return view;
}

// Threshold exceedance as `render --debug-view`: the threshold sits in the middle of the map,
// and texels that are not lit surfaces (b = 1) are black.
DisplayView discontinuity(const ReducedGBuffer& reduced, int level, int channel, float threshold,
                          const char* quantity) {
  DisplayView view =
      scalar(reduced.discontinuity(level).id(), reduced.layout().size(level), channel,
             std::string(quantity) + "; threshold " + std::to_string(threshold) + " in the middle");
  view.range = {0.0f, 2.0f * threshold};
  view.maskChannel = 2;
  view.maskValue = 1.0f;
  return view;
}

DisplayView categories(GLuint texture, glm::ivec2 size, bool unsignedTexture,
                       std::vector<LegendEntry> palette) {
  DisplayView view = fromTexture(texture, size, gpu::kDisplayCategories);
  view.unsignedTexture = unsignedTexture;
  view.channel = 3;
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

std::vector<LegendEntry> levelPalette(const LevelLayout& layout) {
  std::vector<LegendEntry> palette;
  for (int level = 0; level < layout.levelCount(); ++level) {
    const glm::ivec2 size = layout.size(level);
    palette.push_back({levelColour(level), "level " + std::to_string(level) + " (" +
                                               std::to_string(size.x) + "x" +
                                               std::to_string(size.y) + "); darker: unlit"});
  }
  return palette;
}

}  // namespace

const std::vector<DisplayViewInfo>& displayViewInfos() {
  static const std::vector<DisplayViewInfo> infos = {
      {"radiance", "final linear radiance", false, 0, false},
      {"albedo", "G-buffer: diffuse albedo", false, 0, false},
      {"normal", "G-buffer: normal facing the eye", false, 0, false},
      {"depth", "G-buffer: distance to the eye", false, 0, false},
      {"pixel-kind", "G-buffer: background, surface or light", false, 0, false},
      {"specular", "G-buffer: specular colour k_s", false, 0, false},
      {"shininess", "G-buffer: Phong exponent", false, 0, false},
      {"emission", "G-buffer: emission of lights, ambient of surfaces", false, 0, false},
      {"indirect", "indirect light alone (one bounce; black when off)", false, 0, false},
      {"indirect-exact", "indirect light: pixels gathered exactly, not upsampled", false, 0, false},
      {"levels", "level each pixel's lighting came from", false, 0, true},
      {"worklist", "what the refinement decided per texel", true, 0, true},
      {"depth-discontinuity", "relative depth gradient", true, 0, true},
      {"normal-discontinuity", "normal change between neighbours", true, 0, true},
      {"visibility-flags", "visibility masks and where they differ", true, 0, true},
      {"level-depth", "pyramid: mean distance to the eye", true, 0, true},
      {"level-normal", "pyramid: mean normal", true, 0, true},
      {"coverage", "pyramid: fraction of the footprint that is lit surface", true, 1, true},
      {"diffuse-result", "pyramid: diffuse gather result", true, 0, true},
      {"specular-result", "pyramid: specular gather result", true, 0, true}};
  return infos;
}

const DisplayViewInfo* findDisplayView(const std::string& name) {
  for (const DisplayViewInfo& info : displayViewInfos())
    if (name == info.name)
      return &info;
  return nullptr;
}

bool displayViewAvailable(const DisplayViewInfo& info, const Renderer& renderer,
                          const RenderSettings& settings) {
  if (!info.hierarchical)
    return true;
  return settings.mode == RenderMode::Hierarchical && renderer.hierarchy() != nullptr &&
         renderer.hierarchy()->layout.levelCount() > info.firstLevel;
}

DisplayView displayView(const DisplayViewInfo& info, int level, const Renderer& renderer,
                        const RenderSettings& settings) {
  const GBuffer& gbuffer = renderer.gbuffer();
  const std::string name = info.name;
  if (name == "radiance")
    return fromTexture(renderer.radiance().id(), gbuffer.size, gpu::kDisplayRadiance);
  if (name == "albedo")
    return fromTexture(gbuffer.albedo.id(), gbuffer.size, gpu::kDisplayColour);
  if (name == "normal")
    return fromTexture(gbuffer.normalKind.id(), gbuffer.size, gpu::kDisplayNormal);
  if (name == "depth")
    return depth(gbuffer.positionDepth.id(), gbuffer.size);
  if (name == "pixel-kind") {
    return categories(gbuffer.normalKind.id(), gbuffer.size, false,
                      {{glm::vec3(0.0f), "background"},
                       {glm::vec3(0.5f), "surface"},
                       {glm::vec3(0.95f, 0.8f, 0.2f), "light"}});
  }
  if (name == "specular")
    return fromTexture(gbuffer.specular.id(), gbuffer.size, gpu::kDisplayColour);
  if (name == "shininess") {
    DisplayView view = scalar(gbuffer.specular.id(), gbuffer.size, 3, "Phong exponent");
    view.fitRange = true;
    return view;
  }
  if (name == "emission")
    return fromTexture(gbuffer.emission.id(), gbuffer.size, gpu::kDisplayRadiance);
  if (name == "indirect")
    return fromTexture(renderer.indirect().id(), gbuffer.size, gpu::kDisplayRadiance);
  if (name == "indirect-exact")
    return scalar(renderer.indirect().id(), gbuffer.size, 3, "1: gathered exactly");

  const HierarchyTargets& levels = *renderer.hierarchy();
  const ReducedGBuffer& reduced = levels.reduced;
  level = std::clamp(level, info.firstLevel, levels.layout.coarsest());
  const glm::ivec2 size = levels.layout.size(level);
  const MultiresolutionSettings& multiresolution = settings.multiresolution;
  if (name == "levels") {
    DisplayView view =
        fromTexture(levels.gathered.diffuse(0).id(), gbuffer.size, gpu::kDisplayLevels);
    view.palette = levelPalette(levels.layout);
    return view;
  }
  if (name == "worklist")
    return categories(levels.refinement.state(level).id(), size, true, texelStatePalette());
  if (name == "depth-discontinuity") {
    return discontinuity(reduced, level, 0, multiresolution.depthThreshold,
                         "|grad z| / z times the image size");
  }
  if (name == "normal-discontinuity")
    return discontinuity(reduced, level, 1, multiresolution.normalThreshold, "|N1 - N2|");
  if (name == "visibility-flags") {
    return categories(levels.visibility.flags(level).id(), size, true,
                      {{glm::vec3(0.0f), "no mask"},
                       {glm::vec3(0.5f), "mask traced or inherited"},
                       {glm::vec3(0.95f, 0.55f, 0.1f), "visibility changes, no mask"},
                       {glm::vec3(0.9f, 0.1f, 0.1f), "mask differs from a neighbour's"}});
  }
  if (name == "level-depth")
    return depth(reduced.positionDepth(level).id(), size);
  if (name == "level-normal")
    return fromTexture(reduced.normal(level).id(), size, gpu::kDisplayNormal);
  if (name == "coverage")
    return scalar(reduced.normal(level).id(), size, 3, "fraction of lit surface");
  if (name == "diffuse-result")
    return fromTexture(levels.gathered.diffuse(level).id(), size, gpu::kDisplayRadiance);
  if (name == "specular-result")
    return fromTexture(levels.gathered.specular(level).id(), size, gpu::kDisplayRadiance);
  throw std::logic_error("display view '" + name + "' has no texture");
}

glm::vec2 valueRange(const DisplayView& view) {
  const Image image = readTexture(view.texture, view.size, RowOrder::BottomFirst);
  glm::vec2 range(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
  for (const glm::vec4& pixel : image.pixels) {
    if (view.maskChannel >= 0 && pixel[view.maskChannel] == view.maskValue)
      continue;
    range.x = std::min(range.x, pixel[view.channel]);
    range.y = std::max(range.y, pixel[view.channel]);
  }
  return range.x <= range.y ? range : glm::vec2(0.0f, 1.0f);
}

}  // namespace penumbra::app
