#include "scene/gltf_test_scene.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "test_files.h"

namespace penumbra::test {

namespace {

using Json = nlohmann::json;

const std::filesystem::path kTexture = sourceDirectory() / "scenes" / "assets" / "red_blue.png";

constexpr float kCameraTiltDegrees = -15.0f;
constexpr float kCameraYfovRadians = 0.8f;
constexpr float kCubeTurnDegrees = 30.0f;

// One mesh as glTF arrays, in its node's coordinates; uvs in glTF's convention (v down).
struct Arrays {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint16_t> indices;
};

Arrays cube() {
  Arrays cube;
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {1.0f, -1.0f}) {
      const glm::vec3 normal = side * axes[axis];
      const glm::vec3 u = axes[(axis + 1) % 3];
      const glm::vec3 v = side * axes[(axis + 2) % 3];
      const auto first = static_cast<std::uint16_t>(cube.positions.size());
      for (const glm::vec2 corner :
           {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        cube.positions.push_back(0.5f * (normal + corner.x * u + corner.y * v));
        cube.normals.push_back(normal);
      }
      for (const int corner : {0, 1, 2, 0, 2, 3})
        cube.indices.push_back(static_cast<std::uint16_t>(first + corner));
    }
  }
  return cube;
}

// A quad in the plane of `u` and `v` (its normal u x v), corners from -half to +half about
// `centre`.
Arrays quad(glm::vec3 centre, glm::vec3 u, glm::vec3 v) {
  Arrays quad;
  for (const glm::vec2 corner :
       {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
    quad.positions.push_back(centre + corner.x * u + corner.y * v);
    quad.normals.push_back(glm::normalize(glm::cross(u, v)));
    quad.uvs.push_back({0.5f * (corner.x + 1.0f), 0.5f * (1.0f - corner.y)});
  }
  quad.indices = {0, 1, 2, 0, 2, 3};
  return quad;
}

Arrays floorQuad() {
  return quad({0, 0, 0}, {2, 0, 0}, {0, 0, -2});
}

Arrays screenQuad() {
  return quad({0, 0.75f, 0}, {0.8f, 0, 0}, {0, 0.45f, 0});
}

// The buffer, its views and accessors.
class Buffer {
 public:
  template <typename T>
  int add(const std::vector<T>& values, std::string_view type, int componentType, std::size_t count,
          Json& gltf) {
    while (bytes_.size() % 4 != 0)
      bytes_.push_back('\0');
    const std::size_t offset = bytes_.size();
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    gltf["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
    Json accessor = {{"bufferView", gltf["bufferViews"].size() - 1},
                     {"componentType", componentType},
                     {"count", count},
                     {"type", type}};
    gltf["accessors"].push_back(accessor);
    return static_cast<int>(gltf["accessors"].size()) - 1;
  }

  int addView(const std::string& data, Json& gltf) {
    while (bytes_.size() % 4 != 0)
      bytes_.push_back('\0');
    gltf["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", data.size()}});
    bytes_ += data;
    return static_cast<int>(gltf["bufferViews"].size()) - 1;
  }

  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;

int addMesh(const std::string& name, Arrays arrays, int material, std::size_t positionCount,
            bool morphTarget, Buffer& buffer, Json& gltf) {
  Json attributes;
  const int positions = buffer.add(arrays.positions, "VEC3", kFloat, positionCount, gltf);
  glm::vec3 low(std::numeric_limits<float>::infinity());
  glm::vec3 high(-std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : arrays.positions) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  gltf["accessors"][positions]["min"] = {low.x, low.y, low.z};
  gltf["accessors"][positions]["max"] = {high.x, high.y, high.z};
  attributes["POSITION"] = positions;
  attributes["NORMAL"] = buffer.add(arrays.normals, "VEC3", kFloat, arrays.normals.size(), gltf);
  if (!arrays.uvs.empty())
    attributes["TEXCOORD_0"] = buffer.add(arrays.uvs, "VEC2", kFloat, arrays.uvs.size(), gltf);
  Json primitive = {{"attributes", attributes},
                    {"indices", buffer.add(arrays.indices, "SCALAR", kUnsignedShort,
                                           arrays.indices.size(), gltf)},
                    {"material", material}};
  if (morphTarget)
    primitive["targets"] = Json::array({{{"POSITION", positions}}});
  gltf["meshes"].push_back({{"name", name}, {"primitives", Json::array({primitive})}});
  return static_cast<int>(gltf["meshes"].size()) - 1;
}

Json rotationAbout(glm::vec3 axis, float degrees) {
  const float half = glm::radians(degrees) * 0.5f;
  const glm::vec3 xyz = std::sin(half) * axis;
  return {xyz.x, xyz.y, xyz.z, std::cos(half)};
}

std::string vec3Text(glm::vec3 v) {
  std::ostringstream text;
  text << std::setprecision(9) << v.x << " " << v.y << " " << v.z;
  return text.str();
}

void writeObj(const std::filesystem::path& file, const Arrays& arrays) {
  std::ostringstream text;
  text << std::setprecision(9);
  for (const glm::vec3& p : arrays.positions)
    text << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const glm::vec3& n : arrays.normals)
    text << "vn " << n.x << " " << n.y << " " << n.z << "\n";
  // OBJ's v runs up the picture, glTF's down it.
  for (const glm::vec2& uv : arrays.uvs)
    text << "vt " << uv.x << " " << 1.0f - uv.y << "\n";
  for (std::size_t i = 0; i < arrays.indices.size(); i += 3) {
    text << "f";
    for (std::size_t corner = 0; corner < 3; ++corner) {
      const int index = arrays.indices[i + corner] + 1;
      text << " " << index << "/" << (arrays.uvs.empty() ? "" : std::to_string(index)) << "/"
           << index;
    }
    text << "\n";
  }
  writeFile(file.parent_path(), file.filename().string(), text.str());
}

}  // namespace

std::filesystem::path writeGltfTestScene(const std::filesystem::path& directory,
                                         const GltfTestScene& options) {
  Json gltf = {{"asset", {{"version", "2.0"}}},
               {"extensionsUsed", {"KHR_materials_emissive_strength", "KHR_lights_punctual"}}};
  Buffer buffer;
  Arrays cubeArrays = cube();
  if (options.nanPosition)
    cubeArrays.positions[0].x = std::numeric_limits<float>::quiet_NaN();

  const std::string png = readFile(kTexture);
  if (options.binary) {
    gltf["images"] = {{{"bufferView", buffer.addView(png, gltf)}, {"mimeType", "image/png"}}};
  } else {
    std::filesystem::copy_file(kTexture, directory / "red_blue.png",
                               std::filesystem::copy_options::overwrite_existing);
    gltf["images"] = {{{"uri", "red_blue.png"}}};
  }
  gltf["textures"] = {{{"source", 0}}};
  gltf["materials"] = {
      {{"name", "Floor"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}},
      {{"name", "Red"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.8, 0.2, 0.2, 1.0}},
         {"metallicFactor", 0.0},
         {"roughnessFactor", 0.5}}}},
      {{"name", "Screen"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.1, 0.1, 1.0}}}},
       {"emissiveFactor", {1.0, 1.0, 1.0}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}};

  const int floorMesh = addMesh("floor", floorQuad(), 0, 4, false, buffer, gltf);
  const int cubeMesh = addMesh("cube", cubeArrays, 1, options.cubeCount, false, buffer, gltf);
  const int screenMesh = addMesh("screen", screenQuad(), 2, 4, true, buffer, gltf);
  const int times = buffer.add(std::vector<float>{0.0f}, "SCALAR", kFloat, 1, gltf);
  const int offsets = buffer.add(std::vector<glm::vec3>{{0, 1, 0}}, "VEC3", kFloat, 1, gltf);
  gltf["accessors"][times]["min"] = {0.0};
  gltf["accessors"][times]["max"] = {0.0};

  gltf["cameras"] = {{{"name", "View"},
                      {"type", "perspective"},
                      {"perspective",
                       {{"yfov", kCameraYfovRadians},
                        {"aspectRatio", Json::parse(options.aspect)},
                        {"znear", 0.1},
                        {"zfar", 50.0}}}},
                     {{"name", "Spare"},
                      {"type", "perspective"},
                      {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
  gltf["extensions"] = {
      {"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 10.0}}}}}}};
  gltf["nodes"] = {{{"name", "Floor"}, {"mesh", floorMesh}},
                   {{"name", "Cube"},
                    {"mesh", cubeMesh},
                    {"translation", {0.0, 0.5, 0.0}},
                    {"rotation", rotationAbout({0, 1, 0}, kCubeTurnDegrees)},
                    {"scale", {0.6, 0.6, 0.6}}},
                   {{"name", "TV"}, {"translation", {0.0, 0.0, -1.5}}, {"children", {3}}},
                   {{"name", "Screen"}, {"mesh", screenMesh}},
                   {{"name", "View"},
                    {"camera", 0},
                    {"translation", {0.0, 1.5, 3.5}},
                    {"rotation", rotationAbout({1, 0, 0}, kCameraTiltDegrees)}},
                   {{"name", "Lamp"},
                    {"translation", {0.0, 3.0, 0.0}},
                    {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}};
  gltf["scenes"] = {{{"nodes", {0, 1, 2, 4, 5}}}};
  gltf["scene"] = 0;
  gltf["skins"] = {{{"joints", {1}}}};
  gltf["animations"] = {
      {{"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}},
       {"samplers", {{{"input", times}, {"output", offsets}}}}}};

  std::string& bin = buffer.bytes();
  while (bin.size() % 4 != 0)
    bin.push_back('\0');
  if (!options.binary) {
    writeFile(directory, "scene.bin", bin);
    gltf["buffers"] = {{{"uri", "scene.bin"}, {"byteLength", bin.size()}}};
    return writeFile(directory, "scene.gltf", gltf.dump(2));
  }
  gltf["buffers"] = {{{"byteLength", bin.size()}}};
  std::string json = gltf.dump();
  while (json.size() % 4 != 0)
    json.push_back(' ');
  std::string glb;
  const auto put = [&glb](std::uint32_t value) {
    glb.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  put(0x46546C67);  // "glTF"
  put(2);
  put(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  put(static_cast<std::uint32_t>(json.size()));
  put(0x4E4F534A);  // "JSON"
  glb += json;
  put(static_cast<std::uint32_t>(bin.size()));
  put(0x004E4942);  // "BIN\0"
  glb += bin;
  return writeFile(directory, "scene.glb", glb);
}

std::string equivalentSceneBlocks(const std::filesystem::path& directory) {
  writeObj(directory / "floor.obj", floorQuad());
  writeObj(directory / "cube.obj", cube());
  writeObj(directory / "screen.obj", screenQuad());
  std::filesystem::copy_file(kTexture, directory / "red_blue.png",
                             std::filesystem::copy_options::overwrite_existing);
  const float tilt = glm::radians(kCameraTiltDegrees);
  const glm::vec3 position(0.0f, 1.5f, 3.5f);
  const glm::vec3 forward(0.0f, std::sin(tilt), -std::cos(tilt));
  const glm::vec3 up(0.0f, std::cos(tilt), std::sin(tilt));
  std::ostringstream fovy;
  fovy << std::setprecision(9) << glm::degrees(kCameraYfovRadians);
  return "material Floor\n  dif 0.8 0.8 0.8\n  tex red_blue.png\nend\n"
         "material Red\n  dif 0.8 0.2 0.2\nend\n"
         "material Screen\n  dif 0.1 0.1 0.1\n  emit 4 4 4\nend\n"
         "camera View\n  pos " +
         vec3Text(position) + "\n  at " + vec3Text(position + forward) + "\n  up " + vec3Text(up) +
         "\n  fovy " + fovy.str() +
         "\n  near 0.1\n  far 50\n  screen_size 1536 1024\nend\n"
         "object floor.obj\n  mat Floor\nend\n"
         "object cube.obj\n  translate 0 0.5 0\n  rotate 30 0 1 0\n  scale 0.6\n  mat Red\nend\n"
         "object screen.obj\n  translate 0 0 -1.5\n  mat Screen\nend\n";
}

std::string overheadLightBlocks() {
  return "material lamp\n  emit 3 3 3\nend\n"
         "area_light lamp\n  pos1 -0.5 2.5 -0.5\n  pos2 0.5 2.5 -0.5\n  pos3 0.5 2.5 0.5\n"
         "  pos4 -0.5 2.5 0.5\n  at 0 0 0\n  mat lamp\nend\n";
}

}  // namespace penumbra::test
