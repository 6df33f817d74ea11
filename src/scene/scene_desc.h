#pragma once
// A scene as described: the result of parsing a scene file or of building a scene in memory
// (scene_builder.h), before any model or texture file is loaded.
// See ../shared/spec/scene-format.md (copied to docs/scene-format.md) for the meaning of each key.

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"

namespace penumbra {

struct Model;

struct SourceLocation {
  std::string file;
  int line = 0;             // 1-based
  int column = 0;           // 1-based, counted in bytes
  std::string str() const;  // "file:line:col"
};

// Every error about a scene: what() is "file:line:col: error: message".
class SceneError : public std::runtime_error {
 public:
  SceneError(const SourceLocation& where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

struct MaterialDesc {
  std::string name;
  glm::vec3 ambient{0.0f};
  glm::vec3 diffuse{0.8f};
  glm::vec3 specular{0.0f};
  float shininess = 1.0f;
  std::optional<std::filesystem::path> texture;  // resolved against the scene's directory
  SourceLocation textureWhere;                   // of the `tex` value, for texture errors
  std::shared_ptr<const Image> textureImage;     // a texture in memory, instead of `texture`
  std::optional<glm::vec3> emission;             // `emit`; lights fall back to `diffuse`
  // Emissive meshes (issue 18): an object whose material emits is a mesh light. Its emission is
  // `emission` times this texture, read at the mesh's uv (none: 1), and it emits from the side
  // its normals face, or from both sides when `twoSided`. A file (image or video) or an image in
  // memory; `texture` stays the albedo's.
  std::optional<std::filesystem::path> emissionTexture;
  std::shared_ptr<const Image> emissionTextureImage;
  bool twoSided = false;
  SourceLocation where;
};

struct AreaLightDesc {
  std::string name;
  std::array<glm::vec3, 4> corners{};
  std::optional<glm::vec3> emittingSidePoint;  // `at`
  std::string material;
  SourceLocation where;
  SourceLocation materialWhere;  // of the `mat` key, for "undefined material" errors
};

struct CameraDesc {
  std::string name;
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovyDegrees = 45.0f;
  float nearPlane = 0.1f;
  float farPlane = 1000.0f;
  glm::ivec2 screenSize{1024, 1024};
  SourceLocation where;
};

enum class NormalsMode { File, Smooth, Flat };

struct Animation {
  enum class Kind { Rotate, Translate };
  Kind kind = Kind::Rotate;
  glm::vec3 axis{0.0f};  // rotation axis, or translation offset
  float step = 0.0f;     // radians per frame
};

// One static transform statement: `translate`, `rotate` or `scale`.
struct TransformStep {
  enum class Kind { Translate, Rotate, Scale };
  Kind kind = Kind::Translate;
  glm::vec3 vector{0.0f};     // offset, rotation axis or scale factors
  float angleDegrees = 0.0f;  // Rotate
};

struct ObjectDesc {
  std::filesystem::path model;        // resolved against the scene's directory
  std::shared_ptr<const Model> mesh;  // a model in memory, instead of `model`
  std::vector<TransformStep> transform;
  glm::mat4 staticTransform{1.0f};  // the steps composed; set by SceneBuilder
  std::vector<Animation> animations;
  std::optional<std::string> material;
  NormalsMode normals = NormalsMode::File;
  SourceLocation where;
  SourceLocation materialWhere;
};

struct SceneDesc {
  std::filesystem::path file;
  std::vector<MaterialDesc> materials;
  std::vector<AreaLightDesc> lights;
  std::optional<CameraDesc> camera;
  std::vector<ObjectDesc> objects;
  // What an imported glTF scene held that the scene does not use (gltf_import.h).
  std::vector<std::string> warnings;

  const MaterialDesc* findMaterial(const std::string& name) const;
};

// Parses scene text. `file` names the text in messages and is the base of relative paths.
// Throws SceneError at the first problem; no partial scene is returned.
SceneDesc parseScene(std::string_view text, const std::filesystem::path& file);
// A `.gltf` or `.glb` file is read as a scene that imports it and holds nothing else.
SceneDesc parseSceneFile(const std::filesystem::path& file);

}  // namespace penumbra
