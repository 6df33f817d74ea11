#pragma once
// The one registry of debug views: every intermediate buffer of the renderer's last frame that
// `render --debug-view`, `view --debug-view` and the viewer's menu can show, by the same names
// everywhere, each with what it shows and how debug_view_colour.glsl colours it (the one
// colouring: the viewer draws it, `render` reads it back, debug_views.h).
//
// debugViewSource is the one place that reaches the passes' textures and buffers.

#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "gl/handles.h"
#include "render/frame.h"
#include "shared.h"

namespace penumbra {

// What a view needs from the last frame.
enum class DebugViewNeeds {
  AnyFrame,
  Hierarchical,         // a pyramid
  Shadows,              // a voxel grid
  HierarchicalShadows,  // visibility masks
  // The gathered levels whole: level 0's interpolated texels are stored on request after a
  // hierarchical frame, from its G-buffer, which a naive frame replaces.
  HierarchicalResults,
};

struct DebugViewInfo {
  const char* name;
  const char* description;
  // One picture per index, chosen with a number: a pyramid level, or a slice of the voxel grid.
  // `render --debug-view NAME-N` names index N (NAME alone: the first); the viewer has --level.
  bool indexed;
  int firstIndex;  // the first index the view exists at
  DebugViewNeeds needs;
};

struct LegendEntry {
  glm::vec3 colour{0.0f};  // linear, as the colouring receives it
  std::string label;
};

// A view's texture and how to colour it (debug_view_colour.glsl's uniforms).
struct DebugViewSource {
  GLuint texture = 0;
  glm::ivec2 size{0};
  bool unsignedTexture = false;  // an r32ui texture, shown through the palette
  int kind = gpu::kDisplayRadiance;
  int channel = 0;
  // kDisplayScalar: the values at the ends of the colour map, and what the values are.
  glm::vec2 range{0.0f, 1.0f};
  std::string quantity;
  bool fitRange = false;  // the range comes from the picture's own values (valueRange)
  int maskChannel = -1;   // black where this channel equals maskValue
  float maskValue = 0.0f;
  // kDisplayLevels and kDisplayCategories: colour i for value i, with what each value means.
  std::vector<LegendEntry> palette;
  // The texture of a view whose values are gathered on the CPU from the passes' buffers (voxel
  // slices, visible VPLs, visibility refinement); null for the passes' own textures.
  std::shared_ptr<const gl::Texture> ownedTexture;
};

// Every view, in the order of the viewer's menu and of `--help`.
const std::vector<DebugViewInfo>& debugViewInfos();
// The view named `name`, or nullptr.
const DebugViewInfo* findDebugView(const std::string& name);
// The names, comma-separated, for --help and messages.
std::string debugViewNameList();

// Whether the renderer's last frame has this view at all; if not, why (for messages).
bool debugViewAvailable(const DebugViewInfo& info, const Renderer& renderer, std::string* why);
// The indices the view has after the last frame: {first, last}; the view must be available.
glm::ivec2 debugViewIndices(const DebugViewInfo& info, const Renderer& renderer);

// The texture and colouring of view `info` at `index` (clamped to debugViewIndices) after the
// renderer's last frame; the view must be available.
DebugViewSource debugViewSource(const DebugViewInfo& info, int index, const Renderer& renderer,
                                const RenderSettings& settings);

// The smallest and largest value of the view's channel over its unmasked texels (reads the
// texture back); {0, 1} when every texel is masked.
glm::vec2 valueRange(const DebugViewSource& view);

// Level colours of the "levels" view: level 0 (full resolution) first.
glm::vec3 levelColour(int level);
// The colour map of scalar views, from t = 0 to 1: a blue-to-yellow ramp through purple and
// orange that stays readable in grey.
glm::vec3 colourMap(float t);
// Colours of the "worklist" view, per kTexel* state.
glm::vec3 texelStateColour(std::uint32_t state);

}  // namespace penumbra
