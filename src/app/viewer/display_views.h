#pragma once
// What the viewer can show: every intermediate texture of the renderer's last frame, each with
// how display.frag turns it into colours and what its legend says.

#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "render/frame.h"
#include "shared.h"

namespace penumbra::app {

struct LegendEntry {
  glm::vec3 colour{0.0f};  // linear, as display.frag receives it
  std::string label;
};

struct DisplayView {
  GLuint texture = 0;
  glm::ivec2 size{0};
  bool unsignedTexture = false;  // an r32ui texture, shown through the palette
  int kind = gpu::kDisplayRadiance;
  int channel = 0;
  // kDisplayScalar: the values at the ends of the colour map, and what the values are.
  glm::vec2 range{0.0f, 1.0f};
  std::string quantity;
  bool fitRange = false;  // the range comes from the picture's own values, not from settings
  int maskChannel = -1;   // black where this channel equals maskValue
  float maskValue = 0.0f;
  // kDisplayLevels and kDisplayCategories: colour i for value i, with what each value means.
  std::vector<LegendEntry> palette;
};

struct DisplayViewInfo {
  const char* name;
  const char* description;
  bool perLevel;      // one texture per pyramid level, chosen with a level number
  int firstLevel;     // the finest level the view exists at
  bool hierarchical;  // exists only after a hierarchical frame
};

// Every view, in the order of the panel's list.
const std::vector<DisplayViewInfo>& displayViewInfos();
// The view named `name`, or nullptr.
const DisplayViewInfo* findDisplayView(const std::string& name);
// Whether the renderer's last frame has this view (hierarchical ones need a pyramid).
bool displayViewAvailable(const DisplayViewInfo& info, const Renderer& renderer,
                          const RenderSettings& settings);

// The texture and display parameters of view `info` at `level` (clamped to the pyramid's
// levels) after the renderer's last frame; the view must be available.
DisplayView displayView(const DisplayViewInfo& info, int level, const Renderer& renderer,
                        const RenderSettings& settings);

// The smallest and largest value of the view's channel over its unmasked texels (reads the
// texture back); {0, 1} when every texel is masked.
glm::vec2 valueRange(const DisplayView& view);

}  // namespace penumbra::app
