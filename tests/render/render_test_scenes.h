#pragma once
// Small scenes that GPU tests write to disk and load.

#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace penumbra::test {

// Loads scene text written to `directory/name` (relative paths resolve in `directory`).
Scene loadSceneText(const std::filesystem::path& directory, const std::string& text,
                    const std::string& name = "test.scene");

// A 20 x 20 floor quad at y = 0 with normals +y, as OBJ text.
inline constexpr const char* kFloorObj =
    "v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nvn 0 1 0\nf 4//1 3//1 2//1 1//1\n";

// Four colours on a 5x3 texture, so that the VPL cells cut texels.
Image cellCuttingPicture();

// The closed-form form factor from a point to a parallel rectangle of sides a x b whose corner
// lies straight above the point at height h (the standard corner formula).
double cornerFormFactor(double a, double b, double h);

// Leaves out of `compared` the pixels where an unshadowed GPU image and the reference-vpl one
// differ by more than 1% (relative, plus 0.01): faces seen edge-on, where the rasteriser and
// Embree pick different surfaces. Returns how many it left out.
int leaveOutEdgeOnPixels(const Image& gpu, const Image& reference, std::vector<bool>& compared);

}  // namespace penumbra::test
