#pragma once
// A small glTF 2.0 scene written by the tests: a camera, an emissive TV screen quad under a
// parent node, a cube placed by translation, rotation and scale, and a textured floor; plus what
// the import must report as not used (an animation, a skin, a punctual light, a second camera,
// metallic-roughness values, a morph target). Written as .gltf with external buffer and texture
// or as .glb with both embedded, and as the equivalent scene file (OBJ models, material blocks,
// a camera block).

#include <cstddef>
#include <filesystem>
#include <string>

namespace penumbra::test {

struct GltfTestScene {
  bool binary = false;         // .glb with the buffer and the texture embedded
  bool nanPosition = false;    // the cube's first position is NaN
  std::size_t cubeCount = 24;  // the cube's POSITION accessor count (24: right)
  std::string aspect = "1.5";  // the camera's aspectRatio, as JSON
};

// Writes `directory`/scene.gltf (with scene.bin and red_blue.png) or scene.glb; returns its path.
std::filesystem::path writeGltfTestScene(const std::filesystem::path& directory,
                                         const GltfTestScene& options = {});

// The same scene as scene-file blocks (writing the OBJ models and the texture into `directory`).
std::string equivalentSceneBlocks(const std::filesystem::path& directory);

// An area_light quad over the scene, beside the glTF's emissive screen.
std::string overheadLightBlocks();

}  // namespace penumbra::test
