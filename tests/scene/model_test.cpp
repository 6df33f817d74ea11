#include "scene/model.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "test_files.h"

namespace penumbra {
namespace {

// Unit cube [0,1]^3 as triangles, each face with its own `vn` so that its vertices stay split.
// The +y and +z faces are cut along a diagonal through corner 7 = (1,1,1); the +x face is cut
// along the other diagonal, so two triangles of +y, two of +z and one of +x touch corner 7.
constexpr std::string_view kSplitCubeObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vn 0 0 -1
vn 0 0 1
vn -1 0 0
vn 1 0 0
vn 0 -1 0
vn 0 1 0
f 1//1 4//1 3//1
f 1//1 3//1 2//1
f 5//2 6//2 7//2
f 5//2 7//2 8//2
f 1//3 5//3 8//3
f 1//3 8//3 4//3
f 2//4 3//4 6//4
f 3//4 7//4 6//4
f 1//5 2//5 6//5
f 1//5 6//5 5//5
f 4//6 8//6 7//6
f 4//6 7//6 3//6
)";

std::size_t triangleCount(const Model& model) {
  std::size_t count = 0;
  for (const Mesh& mesh : model.meshes)
    count += mesh.triangles.size();
  return count;
}

// Every (position, normal) pair of the model, for checks that ignore how meshes are split.
std::vector<std::pair<glm::vec3, glm::vec3>> verticesOf(const Model& model) {
  std::vector<std::pair<glm::vec3, glm::vec3>> vertices;
  for (const Mesh& mesh : model.meshes)
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      vertices.emplace_back(mesh.positions[i], mesh.normals[i]);
  return vertices;
}

std::set<std::tuple<float, float, float>> distinctNormals(const Model& model) {
  std::set<std::tuple<float, float, float>> normals;
  for (const auto& [position, normal] : verticesOf(model))
    normals.emplace(normal.x, normal.y, normal.z);
  return normals;
}

void expectUnitAndFinite(const Model& model) {
  for (const auto& [position, normal] : verticesOf(model)) {
    ASSERT_TRUE(std::isfinite(normal.x) && std::isfinite(normal.y) && std::isfinite(normal.z));
    // Normalising in float leaves a few ulps of error in the length.
    EXPECT_NEAR(glm::length(normal), 1.0f, 1e-6f);
  }
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << "y " << actual.y << " z " << actual.z;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << "x " << actual.x << " z " << actual.z;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << "x " << actual.x << " y " << actual.y;
}

TEST(ModelObj, QuadWithMaterialFromMtl) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "quad.mtl", R"(newmtl painted
Ka 0.1 0.2 0.3
Kd 0.5 0.25 0.125
Ks 0.75 0.5 0.25
Ns 42
map_Kd textures/albedo.png
)");
  const auto file = test::writeFile(directory, "quad.obj", R"(mtllib quad.mtl
v 0 0 0
v 2 0 0
v 2 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl painted
f 1/1 2/2 3/3 4/4
)");
  const Model model = loadModel(file, NormalsMode::File);
  ASSERT_EQ(model.meshes.size(), 1u);
  const Mesh& mesh = model.meshes[0];
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.material, 0);
  ASSERT_EQ(model.materials.size(), 1u);
  const MaterialDesc& material = model.materials[0];
  EXPECT_EQ(material.name, "painted");
  // MTL numbers are parsed to float: exact for these binary fractions.
  EXPECT_EQ(material.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(material.diffuse, glm::vec3(0.5f, 0.25f, 0.125f));
  EXPECT_EQ(material.specular, glm::vec3(0.75f, 0.5f, 0.25f));
  EXPECT_EQ(material.shininess, 42.0f);
  ASSERT_TRUE(material.texture);
  EXPECT_EQ(material.texture->lexically_normal(), directory / "textures" / "albedo.png");
  // The quad lies in z = 0 and has no `vn`: smooth normals are +z everywhere.
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    EXPECT_EQ(mesh.normals[i], glm::vec3(0, 0, 1));
    // uv = position scaled to the quad: exact for these values.
    EXPECT_EQ(mesh.uvs[i], glm::vec2(mesh.positions[i].x / 2.0f, mesh.positions[i].y));
  }
}

TEST(ModelObj, NoMaterialMeansTheDefault) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeFile(directory, "bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Model model = loadModel(file, NormalsMode::File);
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.meshes[0].material, -1);
  EXPECT_TRUE(model.materials.empty());
  EXPECT_EQ(model.meshes[0].uvs, std::vector<glm::vec2>(3, glm::vec2(0.0f)));
}

TEST(ModelObj, FileNormalsArePreserved) {
  const auto directory = test::scratchDirectory();
  const Model model =
      loadModel(test::writeFile(directory, "cube.obj", kSplitCubeObj), NormalsMode::File);
  EXPECT_EQ(triangleCount(model), 12u);
  EXPECT_EQ(distinctNormals(model).size(), 6u);
  for (const Mesh& mesh : model.meshes) {
    for (const glm::uvec3& triangle : mesh.triangles) {
      const glm::vec3 a = mesh.positions[triangle.x];
      const glm::vec3 face = glm::normalize(
          glm::cross(mesh.positions[triangle.y] - a, mesh.positions[triangle.z] - a));
      // The file's normals are the faces' own: exact axis vectors.
      for (int corner = 0; corner < 3; ++corner)
        EXPECT_EQ(mesh.normals[triangle[corner]], face);
    }
  }
}

TEST(ModelObj, SmoothNormalsWeldSplitVerticesByPosition) {
  const auto directory = test::scratchDirectory();
  const Model model =
      loadModel(test::writeFile(directory, "cube.obj", kSplitCubeObj), NormalsMode::Smooth);
  expectUnitAndFinite(model);
  int cornerVertices = 0;
  for (const auto& [position, normal] : verticesOf(model)) {
    if (position != glm::vec3(1.0f))
      continue;
    ++cornerVertices;
    // Area-weighted sum: each triangle's cross product has length 1, one from +x and two each
    // from +y and +z give (1, 2, 2), of length 3. Float normalisation: a few ulps.
    expectNear(normal, glm::vec3(1.0f, 2.0f, 2.0f) / 3.0f, 1e-6f);
  }
  EXPECT_EQ(cornerVertices, 3);  // split by the file's three normals there, all welded
}

TEST(ModelObj, FlatNormalsSplitEveryFace) {
  const auto directory = test::scratchDirectory();
  const Model model =
      loadModel(test::writeFile(directory, "cube.obj", kSplitCubeObj), NormalsMode::Flat);
  std::size_t vertexCount = 0;
  for (const Mesh& mesh : model.meshes)
    vertexCount += mesh.positions.size();
  EXPECT_EQ(vertexCount, 36u);
  EXPECT_EQ(triangleCount(model), 12u);
  const auto normals = distinctNormals(model);
  EXPECT_EQ(normals.size(), 6u);
  for (const auto& [x, y, z] : normals)  // axis vectors are exact after normalisation
    EXPECT_EQ(std::abs(x) + std::abs(y) + std::abs(z), 1.0f);
}

TEST(ModelPly, AsciiCubeWithFlatNormals) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeFile(directory, "cube.ply", R"(ply
format ascii 1.0
element vertex 8
property float x
property float y
property float z
element face 6
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
4 0 3 2 1
4 4 5 6 7
4 0 4 7 3
4 1 2 6 5
4 0 1 5 4
4 3 7 6 2
)");
  const Model flat = loadModel(file, NormalsMode::Flat);
  EXPECT_EQ(triangleCount(flat), 12u);
  const auto normals = distinctNormals(flat);
  EXPECT_EQ(normals.size(), 6u);
  EXPECT_EQ(normals.count({0.0f, 0.0f, -1.0f}), 1u);
  EXPECT_EQ(normals.count({1.0f, 0.0f, 0.0f}), 1u);

  const Model smooth = loadModel(file, NormalsMode::File);  // no normals in the file
  ASSERT_EQ(smooth.meshes.size(), 1u);
  EXPECT_EQ(smooth.meshes[0].positions.size(), 8u);
  expectUnitAndFinite(smooth);
  // Every corner of a cube points away from the centre: the exact diagonal up to rounding, since
  // each face is cut into two triangles and each corner is touched by 1 or 2 of them.
  for (const auto& [position, normal] : verticesOf(smooth))
    EXPECT_GT(glm::dot(normal, glm::normalize(position - glm::vec3(0.5f))), 0.8f);
}

// Appends the bytes of a little-endian scalar; the tests run on little-endian machines only.
template <typename T>
void append(std::string& bytes, T value) {
  static_assert(std::endian::native == std::endian::little);
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

TEST(ModelPly, BinaryTrianglesAndPositions) {
  const auto directory = test::scratchDirectory();
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 2\nproperty list uchar int "
      "vertex_indices\nend_header\n";
  const glm::vec3 corners[4] = {
      {-1.5f, 0.0f, 2.0f}, {1.5f, 0.0f, 2.0f}, {1.5f, 3.0f, 2.0f}, {-1.5f, 3.0f, 2.0f}};
  for (const glm::vec3& corner : corners) {
    append(bytes, corner.x);
    append(bytes, corner.y);
    append(bytes, corner.z);
  }
  for (const auto& face : {glm::ivec3(0, 1, 2), glm::ivec3(0, 2, 3)}) {
    append(bytes, std::uint8_t{3});
    for (int corner = 0; corner < 3; ++corner)
      append(bytes, std::int32_t{face[corner]});
  }
  const Model model = loadModel(test::writeFile(directory, "quad.ply", bytes), NormalsMode::File);
  ASSERT_EQ(model.meshes.size(), 1u);
  const Mesh& mesh = model.meshes[0];
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.material, -1);
  for (const glm::uvec3& triangle : mesh.triangles) {
    std::set<std::tuple<float, float, float>> seen;
    for (int corner = 0; corner < 3; ++corner) {
      const glm::vec3 p = mesh.positions[triangle[corner]];
      seen.emplace(p.x, p.y, p.z);
      EXPECT_EQ(mesh.normals[triangle[corner]], glm::vec3(0, 0, 1));
    }
    EXPECT_EQ(seen.size(), 3u);
  }
  std::set<std::tuple<float, float, float>> positions;
  for (const glm::vec3& p : mesh.positions)
    positions.emplace(p.x, p.y, p.z);
  for (const glm::vec3& corner : corners)
    EXPECT_EQ(positions.count({corner.x, corner.y, corner.z}), 1u);
}

TEST(ModelPly, DegenerateTrianglesGiveNoNaN) {
  const auto directory = test::scratchDirectory();
  // Triangle 0 is proper, with normal +x. Triangle 1 has two corners at one position (zero area);
  // its corner (5,5,5) is in no other face. Vertex (9,9,9) is used by no face at all.
  const auto file = test::writeFile(directory, "degenerate.ply", R"(ply
format ascii 1.0
element vertex 6
property float x
property float y
property float z
element face 2
property list uchar int vertex_indices
end_header
0 0 0
0 1 0
0 0 1
5 5 5
5 5 5
9 9 9
3 0 1 2
3 3 4 1
)");
  const glm::vec3 properNormal(1, 0, 0);
  const glm::vec3 normalOfNoFace(0, 0, 1);  // the documented choice for unseen vertices
  for (const NormalsMode mode : {NormalsMode::Smooth, NormalsMode::File}) {
    const Model model = loadModel(file, mode);
    expectUnitAndFinite(model);
    for (const auto& [position, normal] : verticesOf(model))
      EXPECT_EQ(normal, position.x < 2.0f ? properNormal : normalOfNoFace);
  }
  const Model flat = loadModel(file, NormalsMode::Flat);
  expectUnitAndFinite(flat);
  ASSERT_EQ(triangleCount(flat), 2u);
  for (const Mesh& mesh : flat.meshes) {
    for (const glm::uvec3& triangle : mesh.triangles) {
      const bool degenerate = mesh.positions[triangle.x].x > 2.0f;
      for (int corner = 0; corner < 3; ++corner)
        EXPECT_EQ(mesh.normals[triangle[corner]], degenerate ? normalOfNoFace : properNormal);
    }
  }
}

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t group = 0;
    const std::size_t count = std::min<std::size_t>(3, bytes.size() - i);
    for (std::size_t j = 0; j < 3; ++j)
      group = (group << 8) | (j < count ? static_cast<std::uint8_t>(bytes[i + j]) : 0u);
    for (std::size_t j = 0; j < 4; ++j)
      text += j <= count ? kDigits[(group >> (18 - 6 * j)) & 63u] : '=';
  }
  return text;
}

// One triangle in z = 0 with normals +z, placed by a node that rotates it 90 degrees about x
// (quaternion (sin 45, 0, 0, cos 45)) and moves it by (0, 0, 5).
std::string gltfTriangle(bool withMaterial) {
  std::string buffer;
  for (const float value : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
    append(buffer, value);
  for (int i = 0; i < 3; ++i)
    for (const float value : {0.0f, 0.0f, 1.0f})
      append(buffer, value);
  // The fourth index only pads the buffer to a multiple of 4 bytes.
  for (const int index : {0, 1, 2, 0})
    append(buffer, static_cast<std::uint16_t>(index));
  const std::string material = withMaterial ? R"(, "material": 0)" : "";
  std::string json = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [0, 0, 5], "rotation": [0.70710678, 0, 0, 0.70710678]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2)" +
                     material + R"(}]}],
  "materials": [{"name": "glazed", "pbrMetallicRoughness": {
    "baseColorFactor": [0.25, 0.5, 0.75, 1.0], "baseColorTexture": {"index": 0}}}],
  "textures": [{"source": 0}],
  "images": [{"uri": "maps/base.png"}],
  "buffers": [{"byteLength": 80, "uri": "data:application/octet-stream;base64,)" +
                     base64(buffer) + R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";
  return json;
}

TEST(ModelGltf, NodeTransformNormalsAndBaseColour) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeFile(directory, "triangle.gltf", gltfTriangle(true));
  const Model model = loadModel(file, NormalsMode::File);
  ASSERT_EQ(model.meshes.size(), 1u);
  const Mesh& mesh = model.meshes[0];
  ASSERT_EQ(mesh.triangles.size(), 1u);
  // The rotation takes y to z and z to -y; the quaternion is rounded to 8 digits and to float.
  const float tolerance = 1e-6f;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    expectNear(mesh.normals[i], glm::vec3(0, -1, 0), tolerance);
    EXPECT_NEAR(mesh.positions[i].y, 0.0f, tolerance);
  }
  std::set<std::tuple<float, float, float>> positions;
  for (const glm::vec3& p : mesh.positions)
    positions.emplace(std::round(p.x), std::round(p.y) + 0.0f, std::round(p.z));
  EXPECT_EQ(positions,
            (std::set<std::tuple<float, float, float>>{{0, 0, 5}, {1, 0, 5}, {0, 0, 6}}));

  ASSERT_EQ(mesh.material, 0);
  const MaterialDesc& material = model.materials[0];
  EXPECT_EQ(material.diffuse, glm::vec3(0.25f, 0.5f, 0.75f));
  ASSERT_TRUE(material.texture);
  EXPECT_EQ(material.texture->lexically_normal(), directory / "maps" / "base.png");
}

TEST(ModelGltf, WithoutMaterialUsesTheDefault) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeFile(directory, "plain.gltf", gltfTriangle(false));
  const Model model = loadModel(file, NormalsMode::Smooth);
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.meshes[0].material, -1);
  // Smooth normals of the placed triangle, computed in model coordinates: the rotated +z.
  for (const glm::vec3& normal : model.meshes[0].normals)
    expectNear(normal, glm::vec3(0, -1, 0), 1e-6f);  // quaternion rounding, as above
}

void expectModelErrorNaming(const std::filesystem::path& file) {
  try {
    loadModel(file, NormalsMode::File);
    FAIL() << "loading " << file << " succeeded";
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

// Loads `text` as `name` expecting a ModelError whose message holds `fragment`.
void expectModelError(const std::string& name, std::string_view text, const std::string& fragment) {
  const auto file = test::writeFile(test::scratchDirectory(), name, text);
  try {
    loadModel(file, NormalsMode::File);
    ADD_FAILURE() << "loading " << name << " succeeded; expected: " << fragment;
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string() + ": " + fragment), std::string::npos)
        << error.what();
  }
}

TEST(ModelErrors, NonFiniteVertexDataNamesTheVertex) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expectModelError("position.obj", "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n",
                   "vertex 2 has the non-finite position (0, 1, nan)");
  // 1e39 is beyond the float range: assimp reads it as infinity.
  expectModelError("beyond_float.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n",
                   "vertex 1 has the non-finite position (inf, 0, 0)");
  expectModelError("normal.obj", triangle + "vn 0 0 1\nvn nan 0 1\nf 1//1 2//2 3//1\n",
                   "vertex 1 has the non-finite normal (nan, 0, 1)");
  // Texture coordinates from PLY: assimp's OBJ reader turns a non-finite `vt` into 0 itself.
  expectModelError("uv.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nproperty float s\nproperty float t\nelement face 1\n"
                   "property list uchar int vertex_indices\nend_header\n"
                   "0 0 0 0 0\n1 0 0 nan 0\n0 1 0 0 1\n3 0 1 2\n",
                   "vertex 1 has the non-finite texture coordinate (nan, 0)");
  expectModelError("normal.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                   "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 -inf 1\n3 0 1 2\n",
                   "vertex 2 has the non-finite normal (0, -inf, 1)");
}

// A face whose index list is empty crashed assimp's SortByPType (found by the model fuzzer).
TEST(ModelErrors, FaceWithoutIndicesIsNamed) {
  expectModelError("empty_face.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                   "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0\n",
                   "face 1 has no vertex indices");
}

// With two `element vertex` lines assimp 5.2's PLY reader wrote past the vertex array it had
// allocated for the first (a heap overflow valgrind found, which corrupted the heap of CI's fuzz
// runs: tests/data/fuzz/model_loader/ply-vertex-element-declared-twice).
TEST(ModelErrors, PlyElementDeclaredTwiceIsNamed) {
  expectModelError("two_vertex_elements.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                   "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n2 2 2\n3 3 3\n3 0 1 2\n",
                   "the PLY header declares element 'vertex' twice (lines 3 and 7)");
}

// assimp allocates what a PLY's element counts and list lengths declare before reading it: the
// 300 million vertices of a 176-byte file took over 4 GiB (CI's model fuzzer ran out of memory),
// a face of 300 million indices 4.8 GB.
TEST(ModelErrors, PlyDeclaringMoreThanItsDataHoldsIsNamed) {
  const std::string vertices =
      "element vertex 3\nproperty float x\nproperty float y\nproperty "
      "float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::string ascii = "ply\nformat ascii 1.0\n";
  expectModelError("too_many_vertices.ply",
                   ascii +
                       "element vertex 300000000\nproperty float x\nproperty float y\n"
                       "property float z\n" +
                       faces + "end_header\n0 0 0\n3 0 0 0\n",
                   "the PLY data ends within element 2 of the 300000000 'vertex' elements "
                   "declared on line 3 (is the file truncated?)");
  expectModelError("count_beyond_64_bits.ply",
                   ascii + vertices +
                       "element face 99999999999999999999999\nproperty list "
                       "uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 "
                       "1 0\n3 0 1 2\n",
                   "the PLY data ends within element 1 of the 18446744073709551615 'face' "
                   "elements declared on line 7");
  // assimp reads the count of an element of a name it does not know from the name's leading
  // digits (the fuzzer's "element 4294967295face 1" was a 55 GB allocation; this one took 7 GB and
  // six minutes).
  expectModelError("count_in_the_name.ply",
                   ascii + vertices + "element 300000000\nproperty float w\n" + faces +
                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                   "the PLY data ends within element 4 of the 300000000 '300000000' elements "
                   "declared on line 7 (assimp reads the count of an element whose name it does "
                   "not know from the digits the name starts with)");
  expectModelError("element_without_properties.ply",
                   ascii + vertices + "element 4444444444ty\n" + faces +
                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                   "the PLY header declares 4444444444 '4444444444ty' elements without properties "
                   "(line 7); an element with instances has properties");
  expectModelError("long_ascii_list.ply",
                   ascii + vertices + faces + "end_header\n0 0 0\n1 0 0\n0 1 0\n300000000 0 1 2\n",
                   "the PLY data ends within the 300000000-value list of 'face' element 0 "
                   "(declared on line 7; is the file truncated?)");
  expectModelError("negative_list_length.ply",
                   ascii + vertices +
                       "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 "
                       "0\n1 0 0\n0 1 0\n-3 0 1 2\n",
                   "'face' element 0 (declared on line 7) has a list of length -3; a list's "
                   "length is never negative");

  const auto binary = [&](std::string_view format, std::string_view data) {
    return "ply\nformat " + std::string(format) + " 1.0\n" + vertices +
           "element face 1\nproperty list int int vertex_indices\nend_header\n" + std::string(data);
  };
  const std::string positions(36, '\0');
  expectModelError("short_binary_vertices.ply",
                   binary("binary_little_endian", std::string(20, '\0')),
                   "the PLY data ends within element 1 of the 3 'vertex' elements declared on "
                   "line 3");
  // The length 300000000 is 0x11e1a300, in either byte order; three indices follow it.
  const std::string indices(12, '\0');
  expectModelError(
      "long_binary_list.ply",
      binary("binary_little_endian", positions + std::string("\x00\xa3\xe1\x11", 4) + indices),
      "the PLY data ends within the 300000000-value list of 'face' element 0");
  expectModelError(
      "long_big_endian_list.ply",
      binary("binary_big_endian", positions + std::string("\x11\xe1\xa3\x00", 4) + indices),
      "the PLY data ends within the 300000000-value list of 'face' element 0");
  expectModelError(
      "negative_binary_list.ply",
      binary("binary_little_endian", positions + std::string("\xfd\xff\xff\xff", 4) + indices),
      "'face' element 0 (declared on line 7) has a list of length -3");
}

// assimp reads a malformed header in ways of its own (the fuzzer found heap corruption after a
// line "element facformat ascii 1.0"): every line must be one of the format's.
TEST(ModelErrors, PlyHeaderLineOutsideTheFormatIsNamed) {
  const std::string vertices =
      "element vertex 3\nproperty float x\nproperty float y\nproperty "
      "float z\n";
  const std::string rest =
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 "
      "0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string format = "format ascii 1.0\n";
  expectModelError("unknown_line.ply", "ply\n" + format + "z\n" + vertices + rest,
                   "line 3 of the PLY header ('z') is none of the PLY header's lines: format, "
                   "comment, obj_info, element or property");
  expectModelError("unknown_format.ply", "ply\nformat asci 1.0\n" + vertices + rest,
                   "line 2 of the PLY header ('format asci 1.0') names no format this reader "
                   "knows");
  expectModelError("no_format.ply", "ply\n" + vertices + rest, "the PLY header has no format line");
  expectModelError("count_missing.ply", "ply\n" + format + "element vertex x\n" + rest,
                   "line 3 of the PLY header ('element vertex x') gives no count");
  expectModelError("property_first.ply", "ply\n" + format + "property float x\n" + vertices + rest,
                   "line 3 of the PLY header ('property float x') declares a property before any "
                   "element");
  expectModelError("unknown_type.ply", "ply\n" + format + vertices + "property flaot w\n" + rest,
                   "line 7 of the PLY header ('property flaot w') names no PLY type");
  expectModelError("float_list_length.ply",
                   "ply\n" + format + vertices +
                       "element face 1\nproperty list float int vertex_indices\nend_header\n",
                   "line 8 of the PLY header ('property list float int vertex_indices') gives no "
                   "integer type for the list's length");
  expectModelError("list_length_not_a_number.ply",
                   "ply\n" + format + vertices +
                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 "
                       "0\n1 0 0\n0 1 0\nthree 0 1 2\n",
                   "'face' element 0 (declared on line 7) has the list length 'three'; a list's "
                   "length is a whole number");
}

// The data check counts each value's own bytes: a file whose data is exactly what its header
// declares loads.
TEST(ModelPly, BinaryDataOfExactlyTheDeclaredSizeLoads) {
  const auto directory = test::scratchDirectory();
  const std::string vertexBytes{0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::string faceBytes{3, 0, 1, 2};
  const Model model = loadModel(
      test::writeFile(directory, "uchar_vertices.ply",
                      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty uchar "
                      "x\nproperty uchar y\nproperty uchar z\nelement face 1\nproperty list "
                      "uchar uchar vertex_indices\nend_header\n" +
                          vertexBytes + faceBytes),
      NormalsMode::File);
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].triangles.size(), 1u);
  EXPECT_EQ(model.meshes[0].positions[model.meshes[0].triangles[0].y], glm::vec3(1, 0, 0));
}

// assimp allocated the JSON chunk at its declared length: 1.9 GB for this one (the model fuzzer's
// tests/data/fuzz/model_loader/glb-json-chunk-beyond-the-file). glb_layout_test.cpp has the rest.
TEST(ModelErrors, GlbChunkBeyondTheFileIsNamed) {
  const std::string json = R"({"asset":{"version":"2.0"}} )";  // 28 bytes
  const std::string header{'g', 'l', 'T', 'F', 2, 0, 0, 0, 48, 0, 0, 0};
  const std::string chunkHeader{0x3c, 0x02, 0x00, 0x72, 'J', 'S', 'O', 'N'};
  expectModelError("huge_json_chunk.glb", header + chunkHeader + json,
                   "the GLB's first chunk is not a JSON chunk within the file");
}

TEST(ModelErrors, ADirectoryIsNamedAsOne) {
  const auto directory = test::scratchDirectory();
  std::filesystem::create_directory(directory / "model.obj");
  try {
    loadModel(directory / "model.obj", NormalsMode::File);
    ADD_FAILURE() << "loading a directory succeeded";
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find("is a directory"), std::string::npos) << error.what();
  }
}

TEST(ModelErrors, NameTheFile) {
  const auto directory = test::scratchDirectory();
  expectModelErrorNaming(directory / "absent.obj");
  expectModelErrorNaming(test::writeFile(directory, "garbage.ply", "ply\nthis is not a header\n"));
  expectModelErrorNaming(test::writeFile(directory, "points.obj", "v 0 0 0\nv 1 0 0\np 1 2\n"));
  expectModelErrorNaming(test::writeFile(directory, "lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"));
}

}  // namespace
}  // namespace penumbra
