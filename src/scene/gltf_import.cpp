#include "scene/gltf_import.h"
#include "scene/glb_layout.h"
#include "scene/tokenizer.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

namespace penumbra {

namespace {

using Json = nlohmann::json;

// A camera without an aspect ratio takes the viewport's (glTF 2.0, 3.10.1); the scene format's
// default screen is square, and a given ratio keeps its height.
constexpr int kScreenHeight = 1024;
// glTF leaves zfar out for an infinite projection; the scene format's default far plane stands in.
constexpr float kFarWithoutZfar = 1000.0f;
// The whole file, and its JSON: all of a .gltf, or the first chunk of a GLB.
class GltfJson {
 public:
  GltfJson(const std::filesystem::path& file, const SourceLocation& where)
      : file_(file), where_(where) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in)
      fail("cannot read the file");
    const std::string content = bytes.str();
    std::string text = content;
    // The layout is read from the file again (a few words), not from a copy of its content.
    if (const std::optional<GlbLayout> glb = readGlbLayout(in, content.size())) {
      if (!glb->problem.empty())
        fail(glb->problem);
      text = content.substr(glb->jsonOffset, glb->jsonLength);
    }
    try {
      json_ = Json::parse(text);
    } catch (const Json::exception& error) {
      fail(std::string("broken JSON: ") + error.what());
    }
    if (!json_.is_object())
      fail("the JSON is not an object");
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw SceneError(where_, "glTF " + quotePath(file_) + ": " + problem);
  }

  // `key` of `object`, when it is there with the given type.
  static const Json* member(const Json& object, std::string_view key, Json::value_t type) {
    if (!object.is_object())
      return nullptr;
    const auto found = object.find(key);
    if (found == object.end() || found->type() != type)
      return nullptr;
    return &*found;
  }

  // The top-level array `key` (empty when absent).
  const Json& array(std::string_view key) const {
    static const Json kEmpty = Json::array();
    const Json* found = member(json_, key, Json::value_t::array);
    return found != nullptr ? *found : kEmpty;
  }

  // A number of `object`, or `fallback` when absent; any other type is an error.
  float number(const Json& object, std::string_view key, float fallback,
               const std::string& owner) const {
    if (!object.is_object() || !object.contains(key))
      return fallback;
    const Json& value = object.at(key);
    if (!value.is_number())
      fail(owner + ": " + quoteToken(key) + " must be a number, found " + value.dump());
    return value.get<float>();
  }

  // The first three components of the number array `key` of `object`, or `fallback`.
  glm::vec3 vec3(const Json& object, std::string_view key, glm::vec3 fallback,
                 const std::string& owner) const {
    if (!object.is_object() || !object.contains(key))
      return fallback;
    const Json& value = object.at(key);
    if (!value.is_array() || value.size() < 3 || !value[0].is_number() || !value[1].is_number() ||
        !value[2].is_number())
      fail(owner + ": " + quoteToken(key) + " must be an array of numbers, found " + value.dump());
    return {value[0].get<float>(), value[1].get<float>(), value[2].get<float>()};
  }

  const Json& root() const { return json_; }

 private:
  std::filesystem::path file_;
  SourceLocation where_;
  Json json_;
};

std::string nameOr(const Json& object, const std::string& fallback) {
  const Json* name = GltfJson::member(object, "name", Json::value_t::string);
  return name != nullptr && !name->get<std::string>().empty() ? name->get<std::string>() : fallback;
}

// "3 skins", "1 skin"; nouns that do not take an "s" are written whole.
std::string counted(std::size_t count, std::string_view singular, std::string_view plural) {
  return std::to_string(count) + " " + std::string(count == 1 ? singular : plural);
}

// One warning per glTF feature that the scene does not use, with its count.
class Census {
 public:
  void add(std::size_t count, std::string_view singular, std::string_view plural,
           std::string_view consequence) {
    if (count > 0)
      warnings_.push_back(counted(count, singular, plural) + " " + std::string(consequence));
  }
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  std::vector<std::string> warnings_;
};

bool has(const Json& object, std::string_view key) {
  return object.is_object() && object.contains(key);
}

const Json& extensionsOf(const Json& object) {
  static const Json kNone = Json::object();
  const Json* found = GltfJson::member(object, "extensions", Json::value_t::object);
  return found != nullptr ? *found : kNone;
}

// Extensions that the import uses, or counts in its own warning.
constexpr std::array<std::string_view, 2> kHandledExtensions{"KHR_materials_emissive_strength",
                                                             "KHR_lights_punctual"};

void countUnusedFeatures(const GltfJson& gltf, std::size_t camerasUsed, Census& census) {
  census.add(gltf.array("animations").size(), "animation", "animations",
             "not imported: the scene is static (objects animate with a scene file's `anim`)");
  census.add(gltf.array("skins").size(), "skin", "skins",
             "not imported: meshes are drawn in their bind pose");
  const Json* lights =
      GltfJson::member(extensionsOf(gltf.root()), "KHR_lights_punctual", Json::value_t::object);
  census.add(lights != nullptr && has(*lights, "lights") && lights->at("lights").is_array()
                 ? lights->at("lights").size()
                 : 0,
             "punctual light (KHR_lights_punctual)", "punctual lights (KHR_lights_punctual)",
             "not imported: Penumbra's lights are area_light quads and emissive surfaces");
  const std::size_t cameras = gltf.array("cameras").size();
  census.add(cameras > camerasUsed ? cameras - camerasUsed : 0, "camera", "cameras",
             "not used: only the first perspective camera placed by a node is");

  std::size_t morphing = 0;
  std::size_t notTriangles = 0;
  std::size_t vertexColours = 0;
  for (const Json& mesh : gltf.array("meshes")) {
    const Json* primitives = GltfJson::member(mesh, "primitives", Json::value_t::array);
    for (const Json& primitive : primitives != nullptr ? *primitives : Json::array()) {
      morphing += has(primitive, "targets") ? 1 : 0;
      const Json* mode = GltfJson::member(primitive, "mode", Json::value_t::number_unsigned);
      notTriangles += mode != nullptr && mode->get<int>() < 4 ? 1 : 0;
      const Json* attributes = GltfJson::member(primitive, "attributes", Json::value_t::object);
      vertexColours += attributes != nullptr && attributes->contains("COLOR_0") ? 1 : 0;
    }
  }
  census.add(morphing, "primitive with morph targets", "primitives with morph targets",
             "drawn in its base shape: morph targets are not imported");
  census.add(notTriangles, "primitive of points or lines", "primitives of points or lines",
             "not drawn: Penumbra draws triangles");
  census.add(vertexColours, "primitive with vertex colours (COLOR_0)",
             "primitives with vertex colours (COLOR_0)", "drawn without them");

  std::size_t metallicRoughness = 0;
  std::size_t normalMaps = 0;
  std::size_t occlusionMaps = 0;
  std::size_t transparent = 0;
  for (const Json& material : gltf.array("materials")) {
    const Json& pbr = has(material, "pbrMetallicRoughness") ? material.at("pbrMetallicRoughness")
                                                            : Json::object();
    metallicRoughness += has(pbr, "metallicFactor") || has(pbr, "roughnessFactor") ||
                                 has(pbr, "metallicRoughnessTexture")
                             ? 1
                             : 0;
    normalMaps += has(material, "normalTexture") ? 1 : 0;
    occlusionMaps += has(material, "occlusionTexture") ? 1 : 0;
    const Json* alphaMode = GltfJson::member(material, "alphaMode", Json::value_t::string);
    transparent += alphaMode != nullptr && alphaMode->get<std::string>() != "OPAQUE" ? 1 : 0;
  }
  census.add(
      metallicRoughness, "material with metallic-roughness values",
      "materials with metallic-roughness values",
      "shaded without them: Penumbra's surfaces are diffuse, with the base colour as albedo");
  census.add(normalMaps, "normal texture", "normal textures", "not used: the mesh normals are");
  census.add(occlusionMaps, "occlusion texture", "occlusion textures",
             "not used: Penumbra computes its own shadows");
  census.add(transparent, "material with alphaMode MASK or BLEND",
             "materials with alphaMode MASK or BLEND", "drawn opaque");

  for (const Json& extension : gltf.array("extensionsUsed")) {
    if (!extension.is_string())
      continue;
    const std::string name = extension.get<std::string>();
    bool handled = false;
    for (const std::string_view known : kHandledExtensions)
      handled = handled || name == known;
    if (!handled)
      census.add(1, "extension " + name, "extensions " + name, "not used");
  }
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row major; glm is column major.
  return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4,
                   m.b4, m.c4, m.d4);
}

class GltfImporter {
 public:
  GltfImporter(SceneBuilder& builder, const std::filesystem::path& file,
               const SourceLocation& where)
      : builder_(builder), file_(file), where_(where), gltf_(file, where) {}

  void run() {
    // SortByPType puts points and lines in meshes of their own, which are skipped (the census
    // counts them); normals are never generated, so that NormalsMode::File decides as for models.
    const aiScene* scene = nullptr;
    try {
      scene = importer_.ReadFile(file_.string(), aiProcess_ValidateDataStructure |
                                                     aiProcess_Triangulate | aiProcess_SortByPType);
    } catch (const std::exception& failure) {
      gltf_.fail(failure.what());
    }
    if (scene == nullptr || scene->mRootNode == nullptr)
      gltf_.fail(importer_.GetErrorString());
    scene_ = scene;

    placeNode(*scene->mRootNode, glm::mat4(1.0f));
    if (objects_ == 0)
      gltf_.fail("the scene has no triangle meshes");
    Census census;
    countUnusedFeatures(gltf_, cameraPlaced_ ? 1 : 0, census);
    for (const std::string& warning : census.warnings())
      builder_.addWarning("glTF " + file_.string() + ": " + warning);
  }

 private:
  // Locates a builder error inside the glTF: "glTF 'FILE' material 'M': <the builder's message>"
  // (no owner: the message names it).
  template <typename Add>
  void checked(const std::string& owner, Add add) {
    try {
      add();
    } catch (const SceneError& error) {
      throw SceneError(
          error.where(),
          "glTF " + quotePath(file_) + (owner.empty() ? "" : " " + owner) + ": " + error.message());
    }
  }

  void placeNode(const aiNode& node, const glm::mat4& worldFromParent) {
    const glm::mat4 worldFromNode = worldFromParent * toGlm(node.mTransformation);
    for (unsigned i = 0; i < node.mNumMeshes; ++i)
      addMesh(*scene_->mMeshes[node.mMeshes[i]], node, worldFromNode);
    placeCamera(node, worldFromNode);
    for (unsigned i = 0; i < node.mNumChildren; ++i)
      placeNode(*node.mChildren[i], worldFromNode);
  }

  void addMesh(const aiMesh& source, const aiNode& node, const glm::mat4& worldFromMesh) {
    if ((source.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0)
      return;
    MeshArrays arrays;
    arrays.name = std::string(node.mName.C_Str()) + "/" + source.mName.C_Str();
    const glm::mat3 normalTransform = normalMatrix(worldFromMesh);
    for (unsigned v = 0; v < source.mNumVertices; ++v) {
      const aiVector3D& p = source.mVertices[v];
      arrays.positions.emplace_back(worldFromMesh * glm::vec4(p.x, p.y, p.z, 1.0f));
      if (source.HasNormals()) {
        const aiVector3D& n = source.mNormals[v];
        arrays.normals.push_back(normalTransform * glm::vec3(n.x, n.y, n.z));
      }
      if (source.HasTextureCoords(0))
        arrays.uvs.emplace_back(source.mTextureCoords[0][v].x, source.mTextureCoords[0][v].y);
    }
    for (unsigned f = 0; f < source.mNumFaces; ++f) {
      const aiFace& face = source.mFaces[f];
      if (face.mNumIndices == 3)
        arrays.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    }
    ObjectDesc object;
    object.where = where_;
    object.material = materialOf(source.mMaterialIndex);
    checked("", [&] {
      object.mesh = makeMeshModel(arrays, NormalsMode::File, where_);
      builder_.addObject(std::move(object));
    });
    ++objects_;
  }

  // The scene material of assimp's material `index` (which is the glTF material of that index;
  // assimp appends one for primitives without a material, which get the default material).
  std::optional<std::string> materialOf(unsigned index) {
    const Json& materials = gltf_.array("materials");
    if (index >= materials.size())
      return std::nullopt;
    if (const auto found = materialName_.find(index); found != materialName_.end())
      return found->second;
    const Json& source = materials[index];
    std::string name = nameOr(source, "material " + std::to_string(index));
    // glTF names need not be unique; the scene's must.
    bool taken = false;
    for (const auto& entry : materialName_)
      taken = taken || entry.second == name;
    if (taken)
      name += " (" + std::to_string(index) + ")";
    materialName_.emplace(index, name);
    if (builder_.hasMaterial(name))
      return name;  // the scene file's material block of this name overrides the glTF's

    const std::string owner = "material " + quoteToken(name);
    MaterialDesc material;
    material.name = name;
    material.where = where_;
    const Json* pbr = GltfJson::member(source, "pbrMetallicRoughness", Json::value_t::object);
    material.diffuse = gltf_.vec3(pbr != nullptr ? *pbr : Json::object(), "baseColorFactor",
                                  glm::vec3(1.0f), owner);
    material.specular = glm::vec3(0.0f);
    const glm::vec3 emissive = gltf_.vec3(source, "emissiveFactor", glm::vec3(0.0f), owner);
    const Json* strength = GltfJson::member(extensionsOf(source), "KHR_materials_emissive_strength",
                                            Json::value_t::object);
    const float emissiveStrength = gltf_.number(strength != nullptr ? *strength : Json::object(),
                                                "emissiveStrength", 1.0f, owner);
    if (emissive != glm::vec3(0.0f))
      material.emission = emissive * emissiveStrength;
    // `doubleSided` says on which sides a surface emits; a diffuse surface is lit from either
    // side anyway. Blender writes it on every material (Backface Culling off), so it is kept for
    // emitting materials only (the scene format refuses `two_sided` without `emit`).
    material.twoSided =
        material.emission && source.is_object() && source.value("doubleSided", false);

    const aiMaterial& imported = *scene_->mMaterials[index];
    textureOf(imported, aiTextureType_BASE_COLOR, material.texture, material.textureImage);
    if (material.emission)
      textureOf(imported, aiTextureType_EMISSIVE, material.emissionTexture,
                material.emissionTextureImage);
    checked(owner, [&] { builder_.addMaterial(std::move(material)); });
    return name;
  }

  // A texture of the material: a file beside the glTF, or an image embedded in it ("*N").
  void textureOf(const aiMaterial& material, aiTextureType type,
                 std::optional<std::filesystem::path>& file, std::shared_ptr<const Image>& image) {
    aiString path;
    if (material.GetTexture(type, 0, &path) != aiReturn_SUCCESS || path.length == 0)
      return;
    if (const aiTexture* embedded = scene_->GetEmbeddedTexture(path.C_Str())) {
      image = embeddedImage(*embedded, path.C_Str());
      return;
    }
    const std::filesystem::path texture(path.C_Str());
    file = texture.is_absolute() ? texture : file_.parent_path() / texture;
  }

  std::shared_ptr<const Image> embeddedImage(const aiTexture& texture, const std::string& key) {
    if (const auto found = embeddedImages_.find(key); found != embeddedImages_.end())
      return found->second;
    const std::string name = "embedded texture " + key + " of " + file_.string();
    // glTF embeds image files (PNG, JPEG); assimp gives them compressed, with mHeight 0.
    if (texture.mHeight != 0 || texture.pcData == nullptr)
      gltf_.fail(name + " is not an image file");
    std::string format(texture.achFormatHint);
    for (char& c : format)
      c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    try {
      auto image = std::make_shared<const Image>(
          decodeImage({reinterpret_cast<const std::uint8_t*>(texture.pcData), texture.mWidth}, name,
                      format.empty() ? "png" : format));
      return embeddedImages_[key] = image;
    } catch (const ImageError& error) {
      gltf_.fail(error.what());
    }
  }

  // The glTF camera looks down its node's -z with +y up (glTF 2.0, 3.10.3).
  void placeCamera(const aiNode& node, const glm::mat4& worldFromNode) {
    if (cameraPlaced_)
      return;
    const Json& cameras = gltf_.array("cameras");
    for (unsigned i = 0; i < scene_->mNumCameras && i < cameras.size(); ++i) {
      if (scene_->mCameras[i]->mName != node.mName)
        continue;
      const Json& source = cameras[i];
      const Json* perspective = GltfJson::member(source, "perspective", Json::value_t::object);
      if (perspective == nullptr)
        continue;  // orthographic: counted among the cameras not used
      cameraPlaced_ = true;
      if (builder_.hasCamera())
        return;  // the scene file's camera overrides the glTF's
      const std::string name = nameOr(source, "camera " + std::to_string(i));
      const std::string owner = "camera " + quoteToken(name);
      CameraDesc camera;
      camera.name = name;
      camera.where = where_;
      camera.position = glm::vec3(worldFromNode * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      camera.target =
          camera.position + glm::vec3(worldFromNode * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
      camera.up = glm::vec3(worldFromNode * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
      camera.fovyDegrees = glm::degrees(gltf_.number(*perspective, "yfov", 0.0f, owner));
      camera.nearPlane = gltf_.number(*perspective, "znear", 0.0f, owner);
      camera.farPlane = gltf_.number(*perspective, "zfar", kFarWithoutZfar, owner);
      camera.screenSize = {kScreenHeight, kScreenHeight};
      if (has(*perspective, "aspectRatio")) {
        const float aspect = gltf_.number(*perspective, "aspectRatio", 1.0f, owner);
        if (!(aspect > 0.0f) || !std::isfinite(aspect))
          gltf_.fail(owner + ": 'aspectRatio' must be a positive number, found " +
                     perspective->at("aspectRatio").dump());
        // A screen 64 times wider than high (65536 pixels) is beyond any image the renderer
        // makes; a width below one pixel is none.
        const float width = std::round(static_cast<float>(kScreenHeight) * aspect);
        if (!(width >= 1.0f && width <= static_cast<float>(kScreenHeight) * 64.0f))
          gltf_.fail(owner + ": 'aspectRatio' " + perspective->at("aspectRatio").dump() +
                     " gives no usable screen width for a height of 1024 pixels");
        camera.screenSize.x = static_cast<int>(width);
      }
      checked(owner, [&] { builder_.setCamera(std::move(camera)); });
      return;
    }
  }

  SceneBuilder& builder_;
  std::filesystem::path file_;
  SourceLocation where_;
  GltfJson gltf_;
  Assimp::Importer importer_;
  const aiScene* scene_ = nullptr;
  std::map<unsigned, std::string> materialName_;
  std::map<std::string, std::shared_ptr<const Image>> embeddedImages_;
  std::size_t objects_ = 0;
  bool cameraPlaced_ = false;
};

}  // namespace

bool isGltfFile(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".gltf" || extension == ".glb";
}

void importGltfScene(SceneBuilder& builder, const std::filesystem::path& file,
                     const SourceLocation& where) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    throw SceneError(where, "glTF file " + quotePath(file) + " not found");
  GltfImporter(builder, file, where).run();
}

}  // namespace penumbra
