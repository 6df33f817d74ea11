#pragma once
// The Penumbra library: load a scene, render it with the multiresolution renderer in your own
// GL 4.5 context (or a headless one), and get the picture as a GL texture or in CPU memory.
// docs/library.md shows how to link it from a CMake project.

#include "penumbra/error.h"
#include "penumbra/image.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "penumbra/version.h"

namespace penumbra::api {

// PENUMBRA_VERSION_STRING of the library that was linked, e.g. "0.2.0".
const char* version();

}  // namespace penumbra::api
