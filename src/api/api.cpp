// The library's facade (include/penumbra/): thin wrappers that translate its types and errors
// to and from the renderer's own.

#include <penumbra/penumbra.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include "gl/context.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/frame.h"
#include "render/gl_state.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace penumbra::api {
namespace {

// Runs `action`, turning the renderer's exceptions into Error of the matching kind.
template <class Action>
auto translatingErrors(Action action) {
  try {
    return action();
  } catch (const SceneError& error) {
    throw Error(Error::Kind::BadInput, error.what());
  } catch (const RenderError& error) {
    throw Error(Error::Kind::BadInput, error.what());
  } catch (const gl::ContextError& error) {
    throw Error(Error::Kind::Gpu, error.what());
  } catch (const gl::ShaderError& error) {
    throw Error(Error::Kind::Gpu, error.what());
  }
}

RenderSettings renderSettings(const Settings& settings) {
  RenderSettings converted;
  converted.mode = settings.mode == Mode::Naive ? RenderMode::Naive : RenderMode::Hierarchical;
  converted.vplsPerLight = settings.vplsPerLight;
  converted.multiresolution.coarsestSize = settings.coarsestSize;
  converted.multiresolution.depthThreshold = settings.depthThreshold;
  converted.multiresolution.normalThreshold = settings.normalThreshold;
  converted.multiresolution.planeTolerance = settings.planeTolerance;
  converted.multiresolution.lightProximityThreshold = settings.lightProximityThreshold;
  converted.shadows.enabled = settings.shadows;
  converted.shadows.visibility = settings.exactVisibility ? ShadowSettings::Visibility::Bvh
                                                          : ShadowSettings::Visibility::Voxels;
  converted.shadows.voxels.resolution = settings.voxelResolution;
  converted.shadows.voxels.shape =
      settings.cubicVoxels ? VoxelSettings::Shape::Cubic : VoxelSettings::Shape::Equal;
  converted.shadows.refinement.threshold = settings.visibilityThreshold;
  converted.indirect.enabled = settings.indirect;
  converted.indirect.vplCount = settings.indirectVpls;
  converted.reuseVisibility = settings.reuseVisibility;
  return converted;
}

}  // namespace

const char* version() {
  return PENUMBRA_VERSION_STRING;
}

Settings::Settings() {
  const RenderSettings defaults;
  mode = defaults.mode == RenderMode::Naive ? Mode::Naive : Mode::Hierarchical;
  vplsPerLight = defaults.vplsPerLight;
  coarsestSize = defaults.multiresolution.coarsestSize;
  depthThreshold = defaults.multiresolution.depthThreshold;
  normalThreshold = defaults.multiresolution.normalThreshold;
  planeTolerance = defaults.multiresolution.planeTolerance;
  lightProximityThreshold = defaults.multiresolution.lightProximityThreshold;
  shadows = defaults.shadows.enabled;
  exactVisibility = defaults.shadows.visibility == ShadowSettings::Visibility::Bvh;
  voxelResolution = defaults.shadows.voxels.resolution;
  cubicVoxels = defaults.shadows.voxels.shape == VoxelSettings::Shape::Cubic;
  visibilityThreshold = defaults.shadows.refinement.threshold;
  indirect = defaults.indirect.enabled;
  indirectVpls = defaults.indirect.vplCount;
  reuseVisibility = defaults.reuseVisibility;
}

namespace {

penumbra::Image toInternal(const Image& image) {
  penumbra::Image converted(image.width, image.height);
  std::memcpy(converted.pixels.data(), image.rgba.data(),
              std::min(image.rgba.size(), converted.pixels.size() * 4) * sizeof(float));
  return converted;
}

}  // namespace

void saveImage(const Image& image, const std::filesystem::path& file, float exposure) {
  const penumbra::Image converted = toInternal(image);
  try {
    penumbra::saveImage(converted, file, {exposure});
  } catch (const ImageError& error) {
    throw Error(Error::Kind::Output, error.what());
  }
}

namespace {

Image fromInternal(const penumbra::Image& image) {
  Image converted{image.width, image.height, std::vector<float>(image.pixels.size() * 4)};
  std::memcpy(converted.rgba.data(), image.pixels.data(), converted.rgba.size() * sizeof(float));
  return converted;
}

}  // namespace

Image loadImage(const std::filesystem::path& file) {
  try {
    return fromInternal(penumbra::loadImage(file));
  } catch (const ImageError& error) {
    throw Error(Error::Kind::BadInput, error.what());
  }
}

Scene Scene::load(const std::filesystem::path& file) {
  return translatingErrors(
      [&] { return Scene(std::make_unique<penumbra::Scene>(loadScene(parseSceneFile(file)))); });
}

namespace {

glm::vec3 vec3Of(const Vec3& value) {
  return {value[0], value[1], value[2]};
}

MaterialDesc materialDesc(const MaterialDescription& material) {
  MaterialDesc desc;
  desc.name = material.name;
  desc.ambient = vec3Of(material.ambient);
  desc.diffuse = vec3Of(material.diffuse);
  desc.specular = vec3Of(material.specular);
  desc.shininess = material.shininess;
  if (material.emission)
    desc.emission = vec3Of(*material.emission);
  desc.texture = material.texture;
  if (material.textureImage)
    desc.textureImage = std::make_shared<const penumbra::Image>(toInternal(*material.textureImage));
  return desc;
}

AreaLightDesc lightDesc(const QuadLightDescription& light) {
  AreaLightDesc desc;
  desc.name = light.name;
  for (std::size_t corner = 0; corner < 4; ++corner)
    desc.corners[corner] = vec3Of(light.corners[corner]);
  if (light.emittingSidePoint)
    desc.emittingSidePoint = vec3Of(*light.emittingSidePoint);
  desc.material = light.material;
  return desc;
}

CameraDesc cameraDesc(const CameraDescription& camera) {
  CameraDesc desc;
  desc.name = camera.name;
  desc.position = vec3Of(camera.position);
  desc.target = vec3Of(camera.target);
  desc.up = vec3Of(camera.up);
  desc.fovyDegrees = camera.fovyDegrees;
  desc.nearPlane = camera.nearPlane;
  desc.farPlane = camera.farPlane;
  desc.screenSize = {camera.width, camera.height};
  return desc;
}

NormalsMode normalsMode(Normals normals) {
  switch (normals) {
    case Normals::Smooth:
      return NormalsMode::Smooth;
    case Normals::Flat:
      return NormalsMode::Flat;
    case Normals::File:
      break;
  }
  return NormalsMode::File;
}

ObjectDesc objectDesc(const ObjectDescription& object, const SceneBuilder& builder) {
  ObjectDesc desc;
  desc.normals = normalsMode(object.normalsMode);
  if (object.model) {
    desc.model = *object.model;
  } else {
    MeshArrays mesh;
    mesh.name = object.meshName;
    for (const Vec3& position : object.positions)
      mesh.positions.push_back(vec3Of(position));
    for (const Vec3& normal : object.normals)
      mesh.normals.push_back(vec3Of(normal));
    for (const auto& uv : object.uvs)
      mesh.uvs.emplace_back(uv[0], uv[1]);
    for (const auto& triangle : object.triangles)
      mesh.triangles.emplace_back(triangle[0], triangle[1], triangle[2]);
    desc.mesh = makeMeshModel(mesh, desc.normals, builder.origin());
  }
  for (const TransformStep& step : object.transform) {
    penumbra::TransformStep converted;
    converted.kind =
        step.kind == TransformStep::Kind::Rotate  ? penumbra::TransformStep::Kind::Rotate
        : step.kind == TransformStep::Kind::Scale ? penumbra::TransformStep::Kind::Scale
                                                  : penumbra::TransformStep::Kind::Translate;
    converted.vector = vec3Of(step.vector);
    converted.angleDegrees = step.angleDegrees;
    desc.transform.push_back(converted);
  }
  desc.material = object.material;
  return desc;
}

}  // namespace

Scene Scene::build(const SceneDescription& description) {
  return translatingErrors([&] {
    SceneBuilder builder;
    for (const MaterialDescription& material : description.materials)
      builder.addMaterial(materialDesc(material));
    for (const QuadLightDescription& light : description.lights)
      builder.addLight(lightDesc(light));
    if (description.camera)
      builder.setCamera(cameraDesc(*description.camera));
    for (const ObjectDescription& object : description.objects)
      builder.addObject(objectDesc(object, builder));
    return Scene(std::make_unique<penumbra::Scene>(loadScene(builder.finish())));
  });
}

Scene::Scene(std::unique_ptr<penumbra::Scene> scene) : scene_(std::move(scene)) {}
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

int Scene::width() const {
  return scene_->camera.size.x;
}

int Scene::height() const {
  return scene_->camera.size.y;
}

const std::vector<std::string>& Scene::warnings() const {
  return scene_->warnings;
}

struct HeadlessContext::State {
  gl::HeadlessContext context;
};

HeadlessContext::HeadlessContext()
    : state_(translatingErrors([] { return std::make_unique<State>(); })) {}
HeadlessContext::HeadlessContext(HeadlessContext&&) noexcept = default;
HeadlessContext& HeadlessContext::operator=(HeadlessContext&&) noexcept = default;
HeadlessContext::~HeadlessContext() = default;

std::string currentGlRenderer() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer == nullptr ? "" : renderer;
}

struct Renderer::State {
  State(penumbra::Scene& scene, glm::ivec2 imageSize)
      : renderer(scene, imageSize), size(imageSize) {}
  penumbra::Renderer renderer;
  glm::ivec2 size;
};

Renderer::Renderer(Scene& scene, int width, int height) {
  const GlStateGuard guard;
  state_ = translatingErrors(
      [&] { return std::make_unique<State>(*scene.scene_, glm::ivec2(width, height)); });
}

Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

void Renderer::render(int frame, const Settings& settings) {
  const GlStateGuard guard;
  translatingErrors([&] { state_->renderer.render(frame, renderSettings(settings)); });
}

std::uint32_t Renderer::texture() const {
  return state_->renderer.radiance().id();
}

Image Renderer::readImage() const {
  const GlStateGuard guard;
  return fromInternal(state_->renderer.readRadiance());
}

int Renderer::width() const {
  return state_->size.x;
}

int Renderer::height() const {
  return state_->size.y;
}

}  // namespace penumbra::api
