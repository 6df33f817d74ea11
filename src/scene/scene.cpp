#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/transform.h"

namespace penumbra {

glm::mat4 Camera::viewFromWorld() const {
  return glm::lookAt(position, target, up);
}

glm::mat4 Camera::clipFromView() const {
  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
  return glm::perspective(glm::radians(fovyDegrees), aspect, nearPlane, farPlane);
}

glm::vec3 Camera::rayDirection(int x, int y) const {
  // The camera basis of gluLookAt, and the image plane at distance 1 in front of the eye.
  const glm::vec3 forward = glm::normalize(target - position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, up));
  const glm::vec3 cameraUp = glm::cross(right, forward);
  const float halfHeight = std::tan(glm::radians(fovyDegrees) * 0.5f);
  const float halfWidth = halfHeight * static_cast<float>(size.x) / static_cast<float>(size.y);
  const float ndcX = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(size.x) - 1.0f;
  const float ndcY = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(size.y);
  return glm::normalize(forward + ndcX * halfWidth * right + ndcY * halfHeight * cameraUp);
}

bool Camera::maySeeBox(glm::vec3 boxMin, glm::vec3 boxMax) const {
  const glm::mat4 clipFromWorld = clipFromView() * viewFromWorld();
  // One bit per plane of the view volume (x, y and z against -w and +w), kept while every corner
  // so far lies outside that plane.
  unsigned outsideOfAll = 0x3fu;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point((corner & 1) != 0 ? boxMax.x : boxMin.x,
                          (corner & 2) != 0 ? boxMax.y : boxMin.y,
                          (corner & 4) != 0 ? boxMax.z : boxMin.z);
    const glm::vec4 clip = clipFromWorld * glm::vec4(point, 1.0f);
    unsigned outside = 0u;
    for (int axis = 0; axis < 3; ++axis) {
      if (clip[axis] < -clip.w)
        outside |= 1u << (2 * axis);
      if (clip[axis] > clip.w)
        outside |= 2u << (2 * axis);
    }
    outsideOfAll &= outside;
  }
  return outsideOfAll == 0u;
}

Camera Camera::turnedAboutTarget(float radians) const {
  Camera turned = *this;
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), radians, glm::normalize(up));
  turned.position = target + glm::vec3(turn * glm::vec4(position - target, 0.0f));
  return turned;
}

namespace {

std::string describe(glm::vec3 v) {
  std::ostringstream text;
  text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return text.str();
}

// Builds a Scene from its description, loading each model and texture once.
class SceneLoader {
 public:
  explicit SceneLoader(const SceneDesc& desc) : desc_(desc) {
    scene_.file = desc.file;
    scene_.warnings = desc.warnings;
  }

  Scene load() {
    for (const AreaLightDesc& light : desc_.lights)
      addLight(light);
    for (const ObjectDesc& object : desc_.objects)
      addObject(object);
    if (desc_.camera) {
      const CameraDesc& camera = *desc_.camera;
      scene_.camera = {camera.position,  camera.target,   camera.up,        camera.fovyDegrees,
                       camera.nearPlane, camera.farPlane, camera.screenSize};
    } else {
      frameWholeScene();
    }
    return std::move(scene_);
  }

 private:
  // A loaded model and the scene materials of its own materials (filled on first need), shared
  // by every object that names the same file with the same normals mode.
  struct LoadedModel {
    std::size_t object = 0;
    std::optional<std::vector<int>> sceneMaterials;
  };

  const MaterialDesc& findMaterial(const std::string& name, const SourceLocation& where) const {
    const MaterialDesc* material = desc_.findMaterial(name);
    if (material == nullptr)
      throw SceneError(where, "undefined material '" + name + "'");
    return *material;
  }

  // The material's texture file or image, each loaded once; `where` locates the error when the
  // texture cannot be loaded.
  int texture(const MaterialDesc& material, const SourceLocation& where) {
    return texture(material.textureImage, material.texture, where);
  }

  int emissionTexture(const MaterialDesc& material, const SourceLocation& where) {
    return texture(material.emissionTextureImage, material.emissionTexture, where);
  }

  int texture(const std::shared_ptr<const Image>& image,
              const std::optional<std::filesystem::path>& file, const SourceLocation& where) {
    if (image) {
      const auto found = textureOfImage_.find(image.get());
      if (found != textureOfImage_.end())
        return found->second;
      scene_.textures.push_back(std::make_unique<MemoryImageSource>(image));
      return textureOfImage_[image.get()] = lastTexture();
    }
    if (!file)
      return -1;
    const std::string key = file->lexically_normal().string();
    if (const auto found = textureOfPath_.find(key); found != textureOfPath_.end())
      return found->second;
    try {
      scene_.textures.push_back(openTextureSource(*file));
    } catch (const ImageError& error) {
      throw SceneError(where, error.what());
    }
    return textureOfPath_[key] = lastTexture();
  }

  int lastTexture() const { return static_cast<int>(scene_.textures.size()) - 1; }

  int addSurfaceMaterial(const MaterialDesc& material, const SourceLocation& textureWhere) {
    SurfaceMaterial surface;
    surface.ambient = material.ambient;
    surface.diffuse = material.diffuse;
    surface.specular = material.specular;
    surface.shininess = material.shininess;
    surface.texture = texture(material, textureWhere);
    // `emit 0 0 0` emits nothing: such a material is an ordinary surface.
    if (material.emission && glm::any(glm::greaterThan(*material.emission, glm::vec3(0.0f)))) {
      surface.emits = true;
      surface.emission = *material.emission;
      surface.emissionTexture = emissionTexture(material, textureWhere);
      surface.twoSided = material.twoSided;
    }
    scene_.materials.push_back(surface);
    return static_cast<int>(scene_.materials.size()) - 1;
  }

  int namedMaterial(const std::string& name, const SourceLocation& where) {
    if (const auto found = materialOfName_.find(name); found != materialOfName_.end())
      return found->second;
    const MaterialDesc& material = findMaterial(name, where);
    const int index = addSurfaceMaterial(material, material.textureWhere);
    materialOfName_.emplace(name, index);
    return index;
  }

  int defaultMaterial() {
    if (!defaultMaterial_) {
      scene_.materials.emplace_back();
      defaultMaterial_ = static_cast<int>(scene_.materials.size()) - 1;
    }
    return *defaultMaterial_;
  }

  void addLight(const AreaLightDesc& light) {
    const MaterialDesc& material = findMaterial(light.material, light.materialWhere);
    std::string problem;
    const std::optional<QuadLight> quad =
        makeQuadLight(light.corners, light.emittingSidePoint, problem);
    if (!quad)
      throw SceneError(light.where, "invalid area light '" + light.name + "': " + problem);
    Light result;
    result.name = light.name;
    result.quad = *quad;
    result.emission = material.emission.value_or(material.diffuse);
    result.texture = texture(material, material.textureWhere);
    scene_.lights.push_back(std::move(result));
  }

  void addObject(const ObjectDesc& object) {
    // A mesh in memory has its normals already; a file is loaded once per normals mode.
    std::ostringstream key;
    if (object.mesh)
      key << "memory:" << object.mesh.get();
    else
      key << object.model.lexically_normal().string() << '\n' << static_cast<int>(object.normals);
    auto found = modelOfKey_.find(key.str());
    SceneObject result;
    result.desc = object;
    if (found == modelOfKey_.end()) {
      try {
        result.model = object.mesh ? *object.mesh : loadModel(object.model, object.normals);
        simplifyForMaps(result.model);
      } catch (const ModelError& error) {
        throw SceneError(object.where, error.what());
      }
      found =
          modelOfKey_.emplace(key.str(), LoadedModel{scene_.objects.size(), std::nullopt}).first;
    } else {
      result.model = scene_.objects[found->second.object].model;
    }

    const std::size_t meshCount = result.model.meshes.size();
    if (object.material) {
      result.meshMaterial.assign(meshCount, namedMaterial(*object.material, object.materialWhere));
    } else {
      std::optional<std::vector<int>>& modelMaterials = found->second.sceneMaterials;
      if (!modelMaterials) {
        modelMaterials.emplace();
        for (const MaterialDesc& material : result.model.materials)
          modelMaterials->push_back(addSurfaceMaterial(material, object.where));
      }
      result.meshMaterial.reserve(meshCount);
      for (const Mesh& mesh : result.model.meshes)
        result.meshMaterial.push_back(mesh.material >= 0 ? (*modelMaterials)[mesh.material]
                                                         : defaultMaterial());
    }
    addMeshLights(result, object);
    scene_.objects.push_back(std::move(result));
  }

  // One light per emitting material of the object, made of the meshes drawn with it.
  void addMeshLights(const SceneObject& object, const ObjectDesc& desc) {
    const int objectIndex = static_cast<int>(scene_.objects.size());
    std::map<int, std::size_t> lightOfMaterial;
    for (std::size_t m = 0; m < object.meshMaterial.size(); ++m) {
      const int materialIndex = object.meshMaterial[m];
      const SurfaceMaterial& material = scene_.materials[static_cast<std::size_t>(materialIndex)];
      if (!material.emits)
        continue;
      auto [found, added] = lightOfMaterial.emplace(materialIndex, scene_.lights.size());
      if (added) {
        Light light;
        light.name = desc.model.filename().string() + " mesh light " +
                     std::to_string(lightOfMaterial.size());
        light.emission = material.emission;
        light.texture = material.emissionTexture;
        light.object = objectIndex;
        light.twoSided = material.twoSided;
        scene_.lights.push_back(std::move(light));
      }
      scene_.lights[found->second].meshes.push_back(m);
    }
    for (const auto& [material, light] : lightOfMaterial) {
      double area = 0.0;
      for (const std::size_t m : scene_.lights[light].meshes) {
        const Mesh& mesh = object.model.meshes[m];
        for (const glm::uvec3& t : mesh.triangles)
          area += glm::length(glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                         mesh.positions[t[2]] - mesh.positions[t[0]]));
      }
      if (!(area > 0.0))
        throw SceneError(desc.where, "emissive mesh of " + desc.model.string() +
                                         " has zero area: it cannot emit light");
    }
  }

  // The spec's default camera: on the +z side of the frame-0 bounding box, looking at its
  // centre, far enough back that the box's bounding sphere fits in the field of view.
  void frameWholeScene() {
    const FrameGeometry geometry = buildFrameGeometry(scene_, 0);
    Camera& camera = scene_.camera;
    const glm::vec3 centre = 0.5f * (geometry.boundsMin + geometry.boundsMax);
    float radius = 0.5f * glm::length(geometry.boundsMax - geometry.boundsMin);
    // An empty or single-point scene still needs a usable camera; the unit is arbitrary.
    if (!(radius > 0.0f))
      radius = 1.0f;
    const float aspect = static_cast<float>(camera.size.x) / static_cast<float>(camera.size.y);
    const float halfFovy = glm::radians(camera.fovyDegrees) * 0.5f;
    const float halfFovx = std::atan(std::tan(halfFovy) * aspect);
    const float distance = radius / std::sin(std::min(halfFovy, halfFovx));
    camera.target = centre;
    camera.position = centre + glm::vec3(0.0f, 0.0f, distance);
    camera.up = {0.0f, 1.0f, 0.0f};
    // The sphere lies between distance - radius and distance + radius; the factors leave room
    // so that rounding never clips it.
    camera.nearPlane = 0.5f * (distance - radius);
    camera.farPlane = 2.0f * (distance + radius);
    scene_.warnings.push_back("no camera in " + desc_.file.string() + ": made one at " +
                              describe(camera.position) + " looking at " + describe(centre) +
                              ", framing the whole scene");
  }

  const SceneDesc& desc_;
  Scene scene_;
  std::unordered_map<std::string, int> textureOfPath_;
  std::unordered_map<const Image*, int> textureOfImage_;
  std::unordered_map<std::string, int> materialOfName_;
  std::unordered_map<std::string, LoadedModel> modelOfKey_;
  std::optional<int> defaultMaterial_;
};

// The triangles a reflective shadow map draws of a mesh (FrameGeometry::mapTriangles).
const std::vector<glm::uvec3>& mapTrianglesOf(const Mesh& mesh) {
  return mesh.mapTriangles.empty() ? mesh.triangles : mesh.mapTriangles;
}

}  // namespace

Scene loadScene(const SceneDesc& desc) {
  return SceneLoader(desc).load();
}

FrameGeometry buildFrameGeometry(const Scene& scene, int frame) {
  FrameGeometry geometry;

  // Counting first lets every output be sized once and each material's triangles be written
  // straight into their batch, without sorting.
  std::size_t vertexCount = 0;
  std::vector<std::uint32_t> nextTriangleOfMaterial(scene.materials.size(), 0);
  std::vector<std::uint32_t> nextMapTriangleOfMaterial(scene.materials.size(), 0);
  for (const SceneObject& object : scene.objects) {
    for (std::size_t m = 0; m < object.model.meshes.size(); ++m) {
      const Mesh& mesh = object.model.meshes[m];
      vertexCount += mesh.positions.size();
      nextTriangleOfMaterial[object.meshMaterial[m]] +=
          static_cast<std::uint32_t>(mesh.triangles.size());
      nextMapTriangleOfMaterial[object.meshMaterial[m]] +=
          static_cast<std::uint32_t>(mapTrianglesOf(mesh).size());
    }
  }
  std::uint32_t triangleCount = 0;
  std::uint32_t mapTriangleCount = 0;
  std::vector<std::size_t> batchOfMaterial(scene.materials.size(), 0);
  for (std::size_t material = 0; material < nextTriangleOfMaterial.size(); ++material) {
    const std::uint32_t count = nextTriangleOfMaterial[material];
    const std::uint32_t mapCount = nextMapTriangleOfMaterial[material];
    if (count > 0) {
      batchOfMaterial[material] = geometry.batches.size();
      geometry.batches.push_back({static_cast<int>(material), triangleCount, count,
                                  mapTriangleCount, mapCount,
                                  glm::vec3(std::numeric_limits<float>::infinity()),
                                  glm::vec3(-std::numeric_limits<float>::infinity())});
    }
    nextTriangleOfMaterial[material] = triangleCount;
    nextMapTriangleOfMaterial[material] = mapTriangleCount;
    triangleCount += count;
    mapTriangleCount += mapCount;
  }
  geometry.positions.resize(vertexCount);
  geometry.normals.resize(vertexCount);
  geometry.uvs.resize(vertexCount);
  geometry.triangles.resize(triangleCount);
  geometry.triangleMaterial.resize(triangleCount);
  geometry.mapTriangles.resize(mapTriangleCount);

  std::uint32_t firstVertex = 0;
  for (const SceneObject& object : scene.objects) {
    const glm::mat4 worldFromModel = worldFromObject(object.desc, frame);
    const glm::mat3 normalTransform = normalMatrix(worldFromModel);
    for (std::size_t m = 0; m < object.model.meshes.size(); ++m) {
      const Mesh& mesh = object.model.meshes[m];
      geometry.meshFirstVertices.push_back(firstVertex);
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const std::size_t out = firstVertex + v;
        geometry.positions[out] = glm::vec3(worldFromModel * glm::vec4(mesh.positions[v], 1.0f));
        const glm::vec3 normal = normalTransform * mesh.normals[v];
        const float lengthSquared = glm::dot(normal, normal);
        // A transform that flattens the object can collapse a normal; keep the model's then.
        geometry.normals[out] =
            lengthSquared > 0.0f ? normal / std::sqrt(lengthSquared) : mesh.normals[v];
        geometry.uvs[out] = mesh.uvs[v];
      }
      const int material = object.meshMaterial[m];
      std::uint32_t& next = nextTriangleOfMaterial[material];
      FrameGeometry::Batch& batch = geometry.batches[batchOfMaterial[material]];
      for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::uvec3 placed = triangle + firstVertex;
        geometry.triangles[next] = placed;
        geometry.triangleMaterial[next] = material;
        ++next;
        for (int corner = 0; corner < 3; ++corner) {
          batch.boundsMin = glm::min(batch.boundsMin, geometry.positions[placed[corner]]);
          batch.boundsMax = glm::max(batch.boundsMax, geometry.positions[placed[corner]]);
        }
      }
      for (const glm::uvec3& triangle : mapTrianglesOf(mesh))
        geometry.mapTriangles[nextMapTriangleOfMaterial[material]++] = triangle + firstVertex;
      firstVertex += static_cast<std::uint32_t>(mesh.positions.size());
    }
  }
  glm::vec3 boundsMin(std::numeric_limits<float>::infinity());
  glm::vec3 boundsMax(-std::numeric_limits<float>::infinity());
  for (const FrameGeometry::Batch& batch : geometry.batches) {
    boundsMin = glm::min(boundsMin, batch.boundsMin);
    boundsMax = glm::max(boundsMax, batch.boundsMax);
  }
  for (const Light& light : scene.lights) {
    if (light.isMesh())
      continue;  // its triangles are among the objects'
    for (const glm::vec3& corner : light.quad.corners) {
      boundsMin = glm::min(boundsMin, corner);
      boundsMax = glm::max(boundsMax, corner);
    }
  }
  if (boundsMin.x <= boundsMax.x) {
    geometry.boundsMin = boundsMin;
    geometry.boundsMax = boundsMax;
  }
  return geometry;
}

}  // namespace penumbra
