#pragma once
// A loaded scene: materials, textures, lights, camera and models, ready for every renderer
// mode. Geometry for a frame is built on demand in world space. No GL here.

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/area_light.h"
#include "scene/emission.h"
#include "scene/model.h"
#include "scene/scene_desc.h"

namespace penumbra {

struct SurfaceMaterial {
  glm::vec3 ambient{0.0f};
  glm::vec3 diffuse{0.8f};
  glm::vec3 specular{0.0f};
  float shininess = 1.0f;
  int texture = -1;  // index into Scene::textures
  // A mesh light's material (docs/mesh-lights.md): its surfaces show emission * T(uv) on their
  // emitting side (both sides when twoSided) and are not lit.
  bool emits = false;
  glm::vec3 emission{0.0f};
  int emissionTexture = -1;  // index into Scene::textures; -1: T = 1
  bool twoSided = false;
};

struct Light {
  std::string name;
  QuadLight quad;            // a quad light's shape; unused (all zero) for a mesh light
  glm::vec3 emission{1.0f};  // E: `emit`, or `dif` when no `emit`
  int texture = -1;          // index into Scene::textures; -1: T = 1
  // A mesh light: the meshes of Scene::objects[object] drawn with one emitting material; their
  // world-space triangles for a frame come from meshLightGeometry (mesh_light.h).
  int object = -1;
  std::vector<std::size_t> meshes;
  bool twoSided = false;
  bool isMesh() const { return object >= 0; }
};

// Perspective of gluPerspective(fovy, width/height, near, far) and gluLookAt(position, target, up).
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 1.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovyDegrees = 45.0f;
  float nearPlane = 0.1f;
  float farPlane = 1000.0f;
  glm::ivec2 size{1024, 1024};

  glm::mat4 viewFromWorld() const;
  glm::mat4 clipFromView() const;
  // Unit direction of the ray through the centre of pixel (x, y), row y counted from the top.
  glm::vec3 rayDirection(int x, int y) const;
  // Whether any of an axis-aligned box may lie within the view volume: false only when all its
  // corners lie outside one plane of it, so a box that passes may still be out of view.
  bool maySeeBox(glm::vec3 boxMin, glm::vec3 boxMax) const;
  // The camera turned by `radians` about the line along its up vector through its target (the
  // eye moves, the target stays): the step of an orbit.
  Camera turnedAboutTarget(float radians) const;
  bool operator==(const Camera&) const = default;
};

struct SceneObject {
  ObjectDesc desc;
  Model model;
  std::vector<int> meshMaterial;  // per mesh: index into Scene::materials
};

struct Scene {
  std::filesystem::path file;
  std::vector<SurfaceMaterial> materials;
  std::vector<std::unique_ptr<TextureSource>> textures;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;
  Camera camera;
  std::vector<std::string> warnings;  // e.g. "no camera: made one framing the scene"
};

// Loads every model and texture the description names. Throws SceneError (with the location of
// the object or material) when a model or texture cannot be loaded.
Scene loadScene(const SceneDesc& desc);

// World-space triangles of one frame, grouped in one batch per material.
struct FrameGeometry {
  struct Batch {
    int material = 0;
    std::uint32_t firstTriangle = 0;
    std::uint32_t triangleCount = 0;
    // Its triangles in `mapTriangles`, which the reflective shadow maps draw.
    std::uint32_t firstMapTriangle = 0;
    std::uint32_t mapTriangleCount = 0;
    // The world-space box of its triangles, for a pass to leave out a batch its view cannot see.
    glm::vec3 boundsMin{0.0f};
    glm::vec3 boundsMax{0.0f};
  };
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::uvec3> triangles;
  std::vector<int> triangleMaterial;
  // The triangles of the reflective shadow maps, over the same vertices: each mesh's
  // Mesh::mapTriangles, or its own triangles where it has none.
  std::vector<glm::uvec3> mapTriangles;
  // Per mesh of each object, in the scene's order: the first of its vertices in `positions` (a
  // mesh's vertices are consecutive), so that a vertex tells which part of which object, with one
  // material, it belongs to.
  std::vector<std::uint32_t> meshFirstVertices;
  std::vector<Batch> batches;
  glm::vec3 boundsMin{0.0f};  // of the triangles and the light quads
  glm::vec3 boundsMax{0.0f};
};

FrameGeometry buildFrameGeometry(const Scene& scene, int frame);

}  // namespace penumbra
