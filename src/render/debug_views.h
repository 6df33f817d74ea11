#pragma once
// Intermediate buffers of the last frame as pictures, for `render --debug-view NAME` (and the
// viewer). docs/multiresolution.md shows each with its legend; the shadow passes' views
// (debug_views_shadows.h, docs/shadows.md) are reached through the same two functions.

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"
#include "render/frame.h"

namespace penumbra {

// Every name valid after a frame of this renderer ("worklist-N" for each level N, "voxels-N"
// for the voxel grid's slices).
std::vector<std::string> debugViewNames(const Renderer& renderer);

// Throws RenderError for an unknown name, or a hierarchical view after a naive frame.
Image debugView(const Renderer& renderer, const std::string& name, const RenderSettings& settings);

// Level colours of the "levels" view: level 0 (full resolution) first.
glm::vec3 levelColour(int level);

// The colour map of scalar views, from t = 0 to 1: a blue-to-yellow ramp through purple and
// orange that stays readable in grey.
glm::vec3 colourMap(float t);

// Colours of the "worklist-N" view, per kTexel* state.
glm::vec3 texelStateColour(std::uint32_t state);

}  // namespace penumbra
