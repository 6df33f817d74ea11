#pragma once
// The shadow passes' intermediate buffers as pictures, for `render --debug-view NAME` beside
// debug_views.h's; docs/shadows.md shows each with its legend.
//
//   voxels-N               slice N of the voxel grid (world grid: the slab at z index N, x to
//                          the right, y up; screen grid: depth slice N as the camera sees it),
//                          occupied voxels white, stretched to the image size
//   visible-vpls           per pixel, the VPLs its visibility mask leaves unoccluded, from the
//                          level the pixel was gathered at, through the colour map (0 to all)
//   visibility-refinement  per pixel, the finest level at which its visibility differed from a
//                          neighbour's (in the "levels" view's colours); grey where a mask was
//                          traced and never differed, black where there is none

#include <optional>
#include <string>
#include <vector>

#include "image/image.h"
#include "render/frame.h"
#include "render/visibility.h"

namespace penumbra {

// The names above ("voxels-N" stands for every slice) valid after the renderer's last frame;
// `masks` are its visibility masks, nullptr when the last frame traced none.
std::vector<std::string> shadowDebugViewNames(const Renderer& renderer,
                                              const VisibilityMasks* masks);

// The view `name` of the last frame, or nullopt when `name` is not a shadow view. Throws
// RenderError when the last frame cannot show it (no shadows, naive mode for the mask views, a
// slice outside the grid).
std::optional<Image> shadowDebugView(const Renderer& renderer, const VisibilityMasks* masks,
                                     const std::string& name);

}  // namespace penumbra
