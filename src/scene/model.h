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

// What is wrong with one value of a vertex that is not finite, as model files and meshes in
// memory report it ("vertex 3 has the non-finite position (nan, 0, 0); positions must be finite
// numbers"), or "" when every one of `values` is finite. `what` names the value ("position").
std::string nonFiniteVertexProblem(std::string_view vertex, std::string_view what,
                                   std::initializer_list<float> values);

}  // namespace penumbra
