#include "render/debug_views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "render/debug_views_shadows.h"
#include "shared.h"

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

namespace {

// Threshold exceedance through the colour map: the threshold itself sits in the middle.
Image discontinuityView(const Renderer& renderer, int channel, float threshold) {
  Image image = readTexture(renderer.hierarchy()->reduced.discontinuity(0).id(),
                            renderer.gbuffer().size, RowOrder::TopFirst);
  for (glm::vec4& pixel : image.pixels) {
    const bool surface = pixel.b == 0.0f;
    pixel = surface ? glm::vec4(colourMap(0.5f * pixel[channel] / threshold), 1.0f)
                    : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  }
  return image;
}

const HierarchyTargets& requireHierarchy(const Renderer& renderer, const std::string& name) {
  if (renderer.hierarchy() == nullptr)
    throw RenderError("debug view '" + name + "' needs the hierarchical mode");
  return *renderer.hierarchy();
}

}  // namespace

glm::vec3 levelColour(int level) {
  static constexpr std::array<glm::vec3, 8> colours = {
      glm::vec3(0.90f, 0.10f, 0.10f), glm::vec3(0.95f, 0.55f, 0.10f),
      glm::vec3(0.95f, 0.90f, 0.15f), glm::vec3(0.25f, 0.80f, 0.25f),
      glm::vec3(0.15f, 0.75f, 0.85f), glm::vec3(0.20f, 0.35f, 0.90f),
      glm::vec3(0.60f, 0.25f, 0.85f), glm::vec3(0.90f, 0.40f, 0.75f)};
  return colours[static_cast<std::size_t>(level) % colours.size()];
}

std::vector<std::string> debugViewNames(const Renderer& renderer) {
  std::vector<std::string> names = {"radiance", "albedo",   "normal",
                                    "depth",    "indirect", "indirect-exact"};
  if (const HierarchyTargets* hierarchy = renderer.hierarchy()) {
    names.insert(names.end(), {"depth-discontinuity", "normal-discontinuity", "levels"});
    for (int level = 0; level < hierarchy->layout.levelCount(); ++level)
      names.push_back("worklist-" + std::to_string(level));
  }
  const std::vector<std::string> shadowNames =
      shadowDebugViewNames(renderer, renderer.visibilityMasks());
  names.insert(names.end(), shadowNames.begin(), shadowNames.end());
  return names;
}

Image debugView(const Renderer& renderer, const std::string& name, const RenderSettings& settings) {
  const GBuffer& gbuffer = renderer.gbuffer();
  if (name == "radiance")
    return renderer.readRadiance();
  if (name == "albedo")
    return readTexture(gbuffer.albedo.id(), gbuffer.size, RowOrder::TopFirst);
  if (name == "normal") {
    Image image = readTexture(gbuffer.normalKind.id(), gbuffer.size, RowOrder::TopFirst);
    for (glm::vec4& pixel : image.pixels)
      pixel =
          pixel.w == 0.0f ? glm::vec4(0, 0, 0, 1) : glm::vec4(0.5f * glm::vec3(pixel) + 0.5f, 1);
    return image;
  }
  if (name == "depth") {
    Image image = readTexture(gbuffer.positionDepth.id(), gbuffer.size, RowOrder::TopFirst);
    float farthest = 0.0f;
    for (const glm::vec4& pixel : image.pixels)
      farthest = std::max(farthest, pixel.w);
    for (glm::vec4& pixel : image.pixels)
      pixel = glm::vec4(glm::vec3(farthest > 0.0f ? pixel.w / farthest : 0.0f), 1.0f);
    return image;
  }
  if (name == "indirect" || name == "indirect-exact") {
    // The indirect light alone (zero when it was off), or white where it was gathered exactly.
    Image image = readTexture(renderer.indirect().id(), gbuffer.size, RowOrder::TopFirst);
    for (glm::vec4& pixel : image.pixels)
      pixel = name == "indirect" ? glm::vec4(glm::vec3(pixel), 1.0f)
                                 : glm::vec4(glm::vec3(pixel.w), 1.0f);
    return image;
  }
  if (name == "depth-discontinuity") {
    requireHierarchy(renderer, name);
    return discontinuityView(renderer, 0, settings.multiresolution.depthThreshold);
  }
  if (name == "normal-discontinuity") {
    requireHierarchy(renderer, name);
    return discontinuityView(renderer, 1, settings.multiresolution.normalThreshold);
  }
  if (name == "levels") {
    const HierarchyTargets& hierarchy = requireHierarchy(renderer, name);
    Image image = readTexture(hierarchy.gathered.diffuse(0).id(), gbuffer.size, RowOrder::TopFirst);
    for (glm::vec4& pixel : image.pixels) {
      // w = 1 + the source level, negative for unlit texels, 0 where nothing was lit.
      const int source = static_cast<int>(std::lround(std::abs(pixel.w))) - 1;
      const glm::vec3 colour = source < 0 ? glm::vec3(0.0f) : levelColour(source);
      pixel = glm::vec4(pixel.w < 0.0f ? 0.3f * colour : colour, 1.0f);
    }
    return image;
  }
  if (name.starts_with("worklist-")) {
    const LevelLayout& layout = requireHierarchy(renderer, name).layout;
    const std::string levelText = name.substr(std::string("worklist-").size());
    int level = -1;
    if (!levelText.empty() && std::all_of(levelText.begin(), levelText.end(), ::isdigit))
      level = std::stoi(levelText);
    if (level < 0 || level >= layout.levelCount()) {
      throw RenderError("debug view '" + name + "': levels are 0 to " +
                        std::to_string(layout.coarsest()));
    }
    const glm::ivec2 size = layout.size(level);
    const std::vector<std::uint32_t> states = readUintTexture(
        renderer.hierarchy()->refinement.state(level).id(), size, RowOrder::TopFirst);
    Image image(size.x, size.y);
    for (std::size_t i = 0; i < states.size(); ++i)
      image.pixels[i] = glm::vec4(texelStateColour(states[i]), 1.0f);
    return image;
  }
  if (std::optional<Image> view = shadowDebugView(renderer, renderer.visibilityMasks(), name))
    return *std::move(view);
  std::string known;
  for (const std::string& option : debugViewNames(renderer))
    known += " " + option;
  throw RenderError("unknown debug view '" + name + "'; expected one of:" + known);
}

}  // namespace penumbra
