#pragma once
// glTF 2.0 scenes (.gltf with external or embedded buffers, .glb) imported whole into a
// SceneBuilder: the node hierarchy's meshes, their materials and textures, and the first camera.
// assimp reads the geometry, the node transforms and the textures; the file's JSON is read here
// too, for what assimp 5.2 does not pass on (KHR_materials_emissive_strength, whether a camera
// gives its aspect ratio) and for the census of what is not imported, which becomes warnings.

#include <filesystem>

#include "scene/scene_builder.h"

namespace penumbra {

// `.gltf` or `.glb`, in any case.
bool isGltfFile(const std::filesystem::path& file);

// Adds the default scene of `file` to `builder`: one object per mesh placed by a node, with the
// node's world transform applied to its vertices; one material per glTF material a mesh uses,
// unless the builder already has a material of that name (a scene file's block overrides the
// glTF material); the first camera, unless the builder has a camera. Every feature that is not
// imported is one builder warning naming it and its count. Throws SceneError at `where` for a
// file that cannot be read or whose values the builder rejects.
void importGltfScene(SceneBuilder& builder, const std::filesystem::path& file,
                     const SourceLocation& where);

}  // namespace penumbra
