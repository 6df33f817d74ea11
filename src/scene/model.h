#pragma once
// Models loaded through assimp (OBJ with MTL, PLY ASCII and binary, glTF 2.0), triangulated,
// in the model's own coordinates, with normals chosen by NormalsMode.

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene_desc.h"

namespace penumbra {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // one per position, unit length
  std::vector<glm::vec2> uvs;      // one per position; (0,0) when the model has none
  std::vector<glm::uvec3> triangles;
  // The triangles a light's reflective shadow map draws, over the same vertices: the mesh
  // simplified (simplifyForMaps) where that at least halves its triangles; else empty, and the
  // maps draw `triangles`.
  std::vector<glm::uvec3> mapTriangles;
  int material = -1;  // index into Model::materials; -1: the default material
};

struct Model {
  std::vector<Mesh> meshes;
  std::vector<MaterialDesc> materials;  // from the file (MTL Kd/Ks/Ns/map_Kd, glTF base colour)
};

class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The matrix that carries normals through `transform`: the direction of the inverse transpose of
// its upper 3x3, computed from cofactors so that a singular transform still gives finite values.
// The result is not normalised.
glm::mat3 normalMatrix(const glm::mat4& transform);

// `file`: keep the model's normals, or compute smooth ones when it has none;
// `smooth`: area-weighted normals over the faces sharing a vertex position;
// `flat`: face normals (vertices are split per face).
// Throws ModelError naming the file for unreadable files and models with no triangles.
Model loadModel(const std::filesystem::path& file, NormalsMode normals);

// Gives every mesh its normals by `normals`, as loadModel does; the given normals count as the
// file's (usable only when every mesh has one non-zero finite normal per position).
void chooseNormals(Model& model, NormalsMode normals);

// Gives each mesh of many small triangles its simplified triangles for the reflective shadow maps
// (Mesh::mapTriangles): meshoptimizer's sloppy simplifier, which merges the vertices in each cell
// of a grid whose cells are about kMapSimplificationError of the mesh's extent. A face of a map of
// 64x64 texels sees the dragon about 30 texels across, drawn from 871k triangles; simplified, from
// 46.5k, about four cells to a texel, with the simplifier's own estimate of its error 0.9% of the
// extent. Drawing the full dragon took 84 ms of the maps' 107 (docs/indirect.md). The camera's
// G-buffer and the shadows keep the full mesh.
constexpr float kMapSimplificationError = 0.01f;
void simplifyForMaps(Model& model);

// What is wrong with one value of a vertex that is not finite, as model files and meshes in
// memory report it ("vertex 3 has the non-finite position (nan, 0, 0); positions must be finite
// numbers"), or "" when every one of `values` is finite. `what` names the value ("position").
std::string nonFiniteVertexProblem(std::string_view vertex, std::string_view what,
                                   std::initializer_list<float> values);

}  // namespace penumbra
