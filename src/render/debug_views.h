#pragma once
// `render --debug-view NAME` (and `--aov`, and the Python module): a view of the registry
// (debug_view_registry.h) after the renderer's last frame, coloured as the viewer colours it and
// read back. docs/cli.md lists the views; docs/multiresolution.md and docs/shadows.md show them.

#include <string>
#include <vector>

#include "image/image.h"
#include "render/debug_view_registry.h"
#include "render/frame.h"

namespace penumbra {

// The names valid after the renderer's last frame: each available view, an indexed one as
// "NAME-N" with N from its first to its last index ("worklist-0", ..., "voxels-0", ...).
std::vector<std::string> debugViewNames(const Renderer& renderer);

// The view `name`: a registry name, or for an indexed view NAME-N (NAME alone: its first index).
// Throws RenderError for an unknown name (listing the registry's), a view the last frame does
// not have, or an index out of its range.
Image debugView(const Renderer& renderer, const std::string& name, const RenderSettings& settings);

}  // namespace penumbra
