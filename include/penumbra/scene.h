#pragma once
// A scene ready to render: its models, textures and videos loaded.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/image.h"

namespace penumbra {
struct Scene;
}

namespace penumbra::api {

using Vec3 = std::array<float, 3>;

// A scene built in memory: the blocks of a scene file as values (docs/scene-format.md gives
// each field's meaning and range; the defaults are the format's). Scene::build checks them as
// the parser checks a file and fails with the same messages.
struct MaterialDescription {
  std::string name;
  Vec3 ambient{0.0f, 0.0f, 0.0f};
  Vec3 diffuse{0.8f, 0.8f, 0.8f};
  Vec3 specular{0.0f, 0.0f, 0.0f};
  float shininess = 1.0f;
  std::optional<Vec3> emission;  // `emit`: a light's radiance (lights fall back to `diffuse`)
  // `tex`: an image or video file, or an image in memory (at most one of the two).
  std::optional<std::filesystem::path> texture;
  std::optional<Image> textureImage;
};

struct QuadLightDescription {
  std::string name;
  std::array<Vec3, 4> corners{};          // pos1 to pos4, convex and coplanar
  std::optional<Vec3> emittingSidePoint;  // `at`
  std::string material;                   // a material's name; its emission is the light's
};

struct CameraDescription {
  std::string name = "camera";
  Vec3 position{0.0f, 0.0f, 0.0f};
  Vec3 target{0.0f, 0.0f, -1.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovyDegrees = 45.0f;
  float nearPlane = 0.1f;
  float farPlane = 1000.0f;
  int width = 1024;
  int height = 1024;
};

// One step of an object's transform, applied in order as the scene format's keys are.
struct TransformStep {
  enum class Kind { Translate, Rotate, Scale };
  Kind kind = Kind::Translate;
  Vec3 vector{0.0f, 0.0f, 0.0f};  // offset, rotation axis or scale factors
  float angleDegrees = 0.0f;      // Rotate
};

enum class Normals { File, Smooth, Flat };

// An object: a model file, or a triangle mesh given as arrays in its own coordinates.
struct ObjectDescription {
  std::optional<std::filesystem::path> model;  // any format assimp reads; or the arrays below
  std::string meshName = "mesh";               // names the arrays in messages
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;                            // one per position, or none
  std::vector<std::array<float, 2>> uvs;                // one per position, or none
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions
  std::vector<TransformStep> transform;
  std::optional<std::string> material;  // default: the model's own, or `dif 0.8 0.8 0.8`
  Normals normalsMode = Normals::File;  // File: the given normals (smooth ones when none)
};

struct SceneDescription {
  std::vector<MaterialDescription> materials;
  std::vector<QuadLightDescription> lights;  // at least one
  std::optional<CameraDescription> camera;   // none: one framing the scene is made
  std::vector<ObjectDescription> objects;
};

class Scene {
 public:
  // Parses a scene file (docs/scene-format.md) and loads what it names, relative to the file.
  // Throws Error (BadInput) with file:line:col.
  static Scene load(const std::filesystem::path& file);
  // Checks and loads a scene built in memory; relative model and texture paths are taken from
  // the working directory. Throws Error (BadInput) with the parser's message for the same value,
  // located at "in-memory scene".
  static Scene build(const SceneDescription& description);

  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  ~Scene();

  // The camera's image size in the scene (`camera ... size`).
  int width() const;
  int height() const;
  // Things the loader fixed up, e.g. "no camera: made one framing the scene".
  const std::vector<std::string>& warnings() const;

 private:
  friend class Renderer;
  explicit Scene(std::unique_ptr<penumbra::Scene> scene);
  std::unique_ptr<penumbra::Scene> scene_;
};

}  // namespace penumbra::api
