#include "scene/model.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <meshoptimizer.h>
#include <assimp/Importer.hpp>

#include "scene/glb_layout.h"
#include "scene/ply_check.h"

namespace penumbra {

namespace {

// A failed internal check of assimp, which loadModel reports as a ModelError.
class AssimpCheckFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace

}  // namespace penumbra

// Debian builds assimp with ASSIMP_BUILD_DEBUG, so a failed internal check (ai_assert) calls this
// function, whose library version prints and aborts: a malformed model would end the process
// (the fuzzer's PLY in tests/data/fuzz failed a check of the triangulation). assimp calls it
// through its PLT, so this definition replaces the library's (ELF symbol interposition), and the
// throw unwinds out of ReadFile into loadModel. Upstream assimp offers setAiAssertHandler for this;
// Debian's 5.2.4 does not export it.
namespace Assimp {
[[noreturn]] void aiAssertViolation(const char* failedExpression, const char* file, int line);
[[noreturn]] void aiAssertViolation(const char* failedExpression, const char* file, int line) {
  throw penumbra::AssimpCheckFailure(std::string("assimp's internal check '") + failedExpression +
                                     "' failed (" + file + ":" + std::to_string(line) + ")");
}
}  // namespace Assimp

namespace penumbra {

namespace {

// A vertex that no face of positive area touches (an unreferenced vertex, or one used only by
// zero-area triangles) is never seen, so any unit vector serves; a fixed one keeps output
// deterministic and NaN-free.
constexpr glm::vec3 kNormalOfNoFace{0.0f, 0.0f, 1.0f};

// assimp reads most formats into memory whole and then builds its own copy of the meshes, so a
// larger file would need many GiB; the largest scanned models in use are a few hundred MiB.
constexpr std::uintmax_t kMaxModelFileBytes = std::uintmax_t{2} << 30;

glm::vec3 unitOr(glm::vec3 direction, glm::vec3 fallback) {
  const float lengthSquared = glm::dot(direction, direction);
  if (!(lengthSquared > 0.0f) || !std::isfinite(lengthSquared))
    return fallback;
  return direction / std::sqrt(lengthSquared);
}

bool isFinite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// `vertex` names the vertex in messages, e.g. "vertex 3" or "vertex 3 of mesh 1".
void checkFiniteVertex(const std::filesystem::path& modelFile, const std::string& vertex,
                       std::string_view what, std::initializer_list<float> values) {
  if (const std::string problem = nonFiniteVertexProblem(vertex, what, values); !problem.empty())
    throw ModelError("model " + modelFile.string() + ": " + problem);
}

// A NaN or infinity in a vertex's data would reach every pixel it touches (and the voxel grid
// and the bounds): the model is rejected, naming the vertex and the values read. Checked before
// assimp welds identical vertices, which can merge a NaN vertex into another and so hide it.
// (assimp's OBJ reader itself reads a non-finite `vt` as 0, which cannot be told from a 0.)
void checkFiniteVertices(const aiScene& scene, const std::filesystem::path& modelFile) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const std::string vertex = "vertex " + std::to_string(i) +
                                 (scene.mNumMeshes > 1 ? " of mesh " + std::to_string(m) : "");
      const aiVector3D& p = mesh.mVertices[i];
      checkFiniteVertex(modelFile, vertex, "position", {p.x, p.y, p.z});
      if (mesh.HasNormals()) {
        const aiVector3D& n = mesh.mNormals[i];
        checkFiniteVertex(modelFile, vertex, "normal", {n.x, n.y, n.z});
      }
      if (mesh.HasTextureCoords(0)) {
        const aiVector3D& uv = mesh.mTextureCoords[0][i];
        checkFiniteVertex(modelFile, vertex, "texture coordinate", {uv.x, uv.y});
      }
    }
  }
}

// assimp's PLY reader turns a face whose index list is empty (a truncated file, or a count of
// 0) into a face of no indices, which ValidateDataStructure lets through and on which
// SortByPType then crashes (SIGBUS in assimp 5.2; found by the model fuzzer,
// tests/data/fuzz/model_loader/ply-face-without-indices). Such a model is rejected first.
void checkFacesHaveIndices(const aiScene& scene, const std::filesystem::path& modelFile) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      if (mesh.mFaces[f].mNumIndices == 0) {
        throw ModelError("model " + modelFile.string() + ": face " + std::to_string(f) +
                         (scene.mNumMeshes > 1 ? " of mesh " + std::to_string(m) : "") +
                         " has no vertex indices; a face needs at least one (is the file "
                         "truncated?)");
      }
    }
  }
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row major; glm is column major.
  return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4,
                   m.b4, m.c4, m.d4);
}

glm::vec3 faceCross(const std::vector<glm::vec3>& positions, const glm::uvec3& triangle) {
  const glm::vec3& a = positions[triangle.x];
  return glm::cross(positions[triangle.y] - a, positions[triangle.z] - a);
}

struct PlacedMesh {
  const aiMesh* mesh = nullptr;
  glm::mat4 modelFromMesh{1.0f};
};

// Flattens the node hierarchy: every reference of a node to a mesh is one placed mesh.
void placeMeshes(const aiScene& scene, const aiNode& node, const glm::mat4& modelFromParent,
                 std::vector<PlacedMesh>& placed) {
  const glm::mat4 modelFromNode = modelFromParent * toGlm(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i)
    placed.push_back({scene.mMeshes[node.mMeshes[i]], modelFromNode});
  for (unsigned i = 0; i < node.mNumChildren; ++i)
    placeMeshes(scene, *node.mChildren[i], modelFromNode, placed);
}

std::string lowercaseExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// assimp invents a material where the file gives none: "DefaultMaterial" for OBJ, an unnamed
// white one for every PLY (PLY materials are not part of the scene format), and for glTF an
// unnamed one appended after the file's own.
bool isInventedMaterial(const aiScene& scene, unsigned index, const std::string& name,
                        const std::string& extension) {
  if (extension == ".ply")
    return true;
  if ((extension == ".gltf" || extension == ".glb") && name.empty())
    return index + 1 == scene.mNumMaterials;
  return name == AI_DEFAULT_MATERIAL_NAME;
}

// Reads one material; nullopt when the spec's default material applies instead: the file has no
// material there, or the material has neither a colour nor a texture.
std::optional<MaterialDesc> readMaterial(const aiScene& scene, unsigned index,
                                         const std::filesystem::path& modelFile) {
  const aiMaterial& material = *scene.mMaterials[index];
  aiString name;
  material.Get(AI_MATKEY_NAME, name);
  if (isInventedMaterial(scene, index, name.C_Str(), lowercaseExtension(modelFile)))
    return std::nullopt;

  aiString texturePath;
  const bool hasTexture =
      material.GetTexture(aiTextureType_DIFFUSE, 0, &texturePath) == aiReturn_SUCCESS ||
      material.GetTexture(aiTextureType_BASE_COLOR, 0, &texturePath) == aiReturn_SUCCESS;
  aiColor4D baseColour;
  const bool hasColour = material.Get(AI_MATKEY_BASE_COLOR, baseColour) == aiReturn_SUCCESS ||
                         material.Get(AI_MATKEY_COLOR_DIFFUSE, baseColour) == aiReturn_SUCCESS;
  if (!hasTexture && !hasColour)
    return std::nullopt;

  MaterialDesc result;
  result.name = name.C_Str();
  if (hasColour)
    result.diffuse = {baseColour.r, baseColour.g, baseColour.b};
  aiColor3D colour;
  if (material.Get(AI_MATKEY_COLOR_SPECULAR, colour) == aiReturn_SUCCESS)
    result.specular = {colour.r, colour.g, colour.b};
  if (material.Get(AI_MATKEY_COLOR_AMBIENT, colour) == aiReturn_SUCCESS)
    result.ambient = {colour.r, colour.g, colour.b};
  float shininess = 0.0f;
  if (material.Get(AI_MATKEY_SHININESS, shininess) == aiReturn_SUCCESS)
    result.shininess = shininess;
  if (hasTexture) {
    if (texturePath.length > 0 && texturePath.C_Str()[0] == '*')
      throw ModelError(modelFile.string() + ": material '" + result.name +
                       "' uses an embedded texture, which an object does not load; "
                       "import the whole glTF with a scene block (docs/scene-format.md)");
    const std::filesystem::path texture(texturePath.C_Str());
    result.texture = texture.is_absolute() ? texture : modelFile.parent_path() / texture;
  }
  return result;
}

Mesh convertMesh(const PlacedMesh& placed, const std::filesystem::path& modelFile) {
  const aiMesh& source = *placed.mesh;
  const glm::mat3 normalTransform = normalMatrix(placed.modelFromMesh);
  Mesh mesh;
  mesh.positions.resize(source.mNumVertices);
  mesh.uvs.resize(source.mNumVertices, glm::vec2(0.0f));
  for (unsigned i = 0; i < source.mNumVertices; ++i) {
    const aiVector3D& p = source.mVertices[i];
    mesh.positions[i] = glm::vec3(placed.modelFromMesh * glm::vec4(p.x, p.y, p.z, 1.0f));
    if (!isFinite(mesh.positions[i]))
      throw ModelError("model " + modelFile.string() + ": vertex " + std::to_string(i) +
                       " is beyond the float range once placed by the file's node transforms");
    if (source.HasTextureCoords(0))
      mesh.uvs[i] = {source.mTextureCoords[0][i].x, source.mTextureCoords[0][i].y};
  }
  if (source.HasNormals()) {
    mesh.normals.resize(source.mNumVertices);
    for (unsigned i = 0; i < source.mNumVertices; ++i) {
      const aiVector3D& n = source.mNormals[i];
      mesh.normals[i] = normalTransform * glm::vec3(n.x, n.y, n.z);
    }
  }
  mesh.triangles.reserve(source.mNumFaces);
  for (unsigned i = 0; i < source.mNumFaces; ++i) {
    const aiFace& face = source.mFaces[i];
    if (face.mNumIndices != 3)
      continue;
    const glm::uvec3 triangle(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    if (triangle.x >= source.mNumVertices || triangle.y >= source.mNumVertices ||
        triangle.z >= source.mNumVertices)
      throw ModelError(modelFile.string() + ": a face refers to a vertex that does not exist");
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

// Zero, non-finite or missing normals make the file's normals unusable: they would need the
// same repair as no normals at all.
bool hasUsableNormals(Mesh& mesh) {
  if (mesh.normals.size() != mesh.positions.size())
    return false;
  for (glm::vec3& normal : mesh.normals) {
    const glm::vec3 unit = unitOr(normal, glm::vec3(0.0f));
    if (unit == glm::vec3(0.0f))
      return false;
    normal = unit;
  }
  return true;
}

// The bit pattern of a position: equal keys are exactly equal positions.
using PositionKey = std::array<std::uint32_t, 3>;

PositionKey keyOf(glm::vec3 position) {
  // Adding +0 turns -0 into +0, so the two zeros weld as the exact comparison says they should.
  position += glm::vec3(0.0f);
  PositionKey key;
  std::memcpy(key.data(), &position, sizeof key);
  return key;
}

// Area-weighted normals: each vertex gets the normalised sum of the unnormalised cross products
// of all faces, in any mesh of the model, that touch its exact position.
void computeSmoothNormals(std::vector<Mesh>& meshes) {
  std::vector<std::size_t> firstVertex(meshes.size());
  std::size_t vertexCount = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    firstVertex[m] = vertexCount;
    vertexCount += meshes[m].positions.size();
  }
  // Welding by sorting keeps a million-vertex model fast: no allocation per position.
  std::vector<std::pair<PositionKey, std::uint32_t>> byPosition;
  byPosition.reserve(vertexCount);
  for (std::size_t m = 0; m < meshes.size(); ++m)
    for (std::size_t v = 0; v < meshes[m].positions.size(); ++v)
      byPosition.emplace_back(keyOf(meshes[m].positions[v]),
                              static_cast<std::uint32_t>(firstVertex[m] + v));
  std::sort(byPosition.begin(), byPosition.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::uint32_t> groupOfVertex(vertexCount);
  std::uint32_t groupCount = 0;
  for (std::size_t i = 0; i < byPosition.size(); ++i) {
    if (i == 0 || byPosition[i].first != byPosition[i - 1].first)
      ++groupCount;
    groupOfVertex[byPosition[i].second] = groupCount - 1;
  }

  std::vector<glm::vec3> groupSum(groupCount, glm::vec3(0.0f));
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const std::uint32_t* group = &groupOfVertex[firstVertex[m]];
    for (const glm::uvec3& triangle : meshes[m].triangles) {
      const glm::vec3 weightedNormal = faceCross(meshes[m].positions, triangle);
      // Zero-area faces add nothing; faces with non-finite corners would poison the sum.
      if (!isFinite(weightedNormal))
        continue;
      for (int corner = 0; corner < 3; ++corner)
        groupSum[group[triangle[corner]]] += weightedNormal;
    }
  }
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    meshes[m].normals.resize(meshes[m].positions.size());
    for (std::size_t v = 0; v < meshes[m].positions.size(); ++v)
      meshes[m].normals[v] = unitOr(groupSum[groupOfVertex[firstVertex[m] + v]], kNormalOfNoFace);
  }
}

// Splits every triangle into three vertices of its own carrying the face normal.
void makeFlat(Mesh& mesh) {
  Mesh flat;
  flat.material = mesh.material;
  const std::size_t vertexCount = mesh.triangles.size() * 3;
  flat.positions.reserve(vertexCount);
  flat.normals.reserve(vertexCount);
  flat.uvs.reserve(vertexCount);
  flat.triangles.reserve(mesh.triangles.size());
  for (const glm::uvec3& triangle : mesh.triangles) {
    const glm::vec3 normal = unitOr(faceCross(mesh.positions, triangle), kNormalOfNoFace);
    const auto first = static_cast<std::uint32_t>(flat.positions.size());
    for (int corner = 0; corner < 3; ++corner) {
      flat.positions.push_back(mesh.positions[triangle[corner]]);
      flat.uvs.push_back(mesh.uvs[triangle[corner]]);
      flat.normals.push_back(normal);
    }
    flat.triangles.emplace_back(first, first + 1, first + 2);
  }
  mesh = std::move(flat);
}

// assimp allocates a GLB's JSON chunk at the length its header gives (glb_layout.h).
void checkGlbFile(const std::filesystem::path& file, std::uintmax_t fileBytes) {
  std::ifstream in(file, std::ios::binary);
  const std::optional<GlbLayout> layout = readGlbLayout(in, fileBytes);
  if (layout && !layout->problem.empty())
    throw ModelError("cannot read model " + file.string() + ": " + layout->problem);
}

}  // namespace

std::string nonFiniteVertexProblem(std::string_view vertex, std::string_view what,
                                   std::initializer_list<float> values) {
  bool finite = true;
  std::ostringstream text;
  text << "(";
  for (const float value : values) {
    finite = finite && std::isfinite(value);
    text << (text.tellp() > 1 ? ", " : "") << value;
  }
  text << ")";
  if (finite)
    return {};
  return std::string(vertex) + " has the non-finite " + std::string(what) + " " + text.str() +
         "; " + std::string(what) + "s must be finite numbers";
}

glm::mat3 normalMatrix(const glm::mat4& transform) {
  // The cofactor matrix is det(A) * inverse(transpose(A)); multiplying by the sign of det(A)
  // keeps the inverse transpose's orientation for mirroring transforms.
  const glm::vec3 x(transform[0]);
  const glm::vec3 y(transform[1]);
  const glm::vec3 z(transform[2]);
  const glm::mat3 cofactors(glm::cross(y, z), glm::cross(z, x), glm::cross(x, y));
  return glm::dot(x, glm::cross(y, z)) < 0.0f ? -cofactors : cofactors;
}

Model loadModel(const std::filesystem::path& file, NormalsMode normals) {
  std::error_code statusError;
  if (std::filesystem::is_directory(file, statusError))
    throw ModelError("cannot read model " + file.string() + ": it is a directory");
  if (!std::filesystem::is_regular_file(file, statusError))
    throw ModelError("cannot read model " + file.string() + ": no such file");
  const std::uintmax_t bytes = std::filesystem::file_size(file, statusError);
  if (statusError)
    throw ModelError("cannot read model " + file.string() + ": " + statusError.message());
  if (bytes > kMaxModelFileBytes) {
    throw ModelError("model " + file.string() + " is " + std::to_string(bytes) +
                     " bytes; model files are limited to " + std::to_string(kMaxModelFileBytes) +
                     " bytes (2 GiB)");
  }
  checkPlyFile(file, bytes);
  checkGlbFile(file, bytes);

  Assimp::Importer importer;
  // SortByPType puts points and lines in meshes of their own, which convertMesh leaves without
  // triangles and which are then skipped (removing them in assimp instead would turn a model of
  // lines into the unclear "No meshes remaining" rather than "has no triangles"). Normals are
  // never generated by assimp, so that the modes below are exactly what the spec says.
  // ValidateDataStructure runs first and rejects out-of-range indices, on which the other steps
  // read out of bounds (the fuzzer's truncated PLY in tests/data/fuzz crashed them); the vertices
  // and faces are checked between it and the other steps.
  const aiScene* scene = nullptr;
  const auto failed = [&importer, &file] {
    return ModelError("cannot read model " + file.string() + ": " + importer.GetErrorString());
  };
  try {
    scene = importer.ReadFile(file.string(), aiProcess_ValidateDataStructure);
    if (scene == nullptr || scene->mRootNode == nullptr)
      throw failed();
    checkFiniteVertices(*scene, file);
    checkFacesHaveIndices(*scene, file);
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                         aiProcess_SortByPType);
  } catch (const AssimpCheckFailure& failure) {
    throw ModelError("cannot read model " + file.string() + ": " + failure.what());
  }
  if (scene == nullptr || scene->mRootNode == nullptr)
    throw failed();

  std::vector<PlacedMesh> placed;
  placeMeshes(*scene, *scene->mRootNode, glm::mat4(1.0f), placed);

  Model model;
  std::unordered_map<unsigned, int> modelMaterialOf;  // assimp material index -> Model index
  for (const PlacedMesh& instance : placed) {
    Mesh mesh = convertMesh(instance, file);
    if (mesh.triangles.empty())
      continue;
    const unsigned sourceMaterial = instance.mesh->mMaterialIndex;
    auto found = modelMaterialOf.find(sourceMaterial);
    if (found == modelMaterialOf.end()) {
      int index = -1;
      if (sourceMaterial < scene->mNumMaterials) {
        if (auto material = readMaterial(*scene, sourceMaterial, file)) {
          index = static_cast<int>(model.materials.size());
          model.materials.push_back(std::move(*material));
        }
      }
      found = modelMaterialOf.emplace(sourceMaterial, index).first;
    }
    mesh.material = found->second;
    model.meshes.push_back(std::move(mesh));
  }
  if (model.meshes.empty())
    throw ModelError("model " + file.string() + " has no triangles");

  chooseNormals(model, normals);
  return model;
}

void chooseNormals(Model& model, NormalsMode normals) {
  bool useFileNormals = normals == NormalsMode::File;
  for (Mesh& mesh : model.meshes)
    useFileNormals = useFileNormals && hasUsableNormals(mesh);
  if (normals == NormalsMode::Flat) {
    for (Mesh& mesh : model.meshes)
      makeFlat(mesh);
  } else if (!useFileNormals) {
    computeSmoothNormals(model.meshes);
  }
}

void simplifyForMaps(Model& model) {
  // The simplifier reads and writes the triangles as a flat array of indices.
  static_assert(sizeof(glm::uvec3) == 3 * sizeof(unsigned int));
  for (Mesh& mesh : model.meshes) {
    mesh.mapTriangles.clear();
    const std::size_t indexCount = mesh.triangles.size() * 3;
    if (indexCount == 0)
      continue;
    std::vector<glm::uvec3> simplified(mesh.triangles.size());
    // No target count: as few triangles as the grid allows.
    const std::size_t kept = meshopt_simplifySloppy(
        &simplified[0].x, &mesh.triangles[0].x, indexCount, &mesh.positions[0].x,
        mesh.positions.size(), sizeof(glm::vec3), 0, kMapSimplificationError, nullptr);
    // A mesh whose triangles are already about as large as the error keeps them, bit for bit.
    if (2 * kept > indexCount)
      continue;
    simplified.resize(kept / 3);
    mesh.mapTriangles = std::move(simplified);
  }
}

}  // namespace penumbra
