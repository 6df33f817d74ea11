// The Python module `penumbra` (docs/python.md): scenes from files or NumPy arrays (through
// scene/scene_builder.h), every renderer mode with every setting as a keyword argument, images as
// float32 NumPy arrays, image metrics and frame statistics as dicts. Renders release the GIL.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "app/statistics_json.h"
#include "gl/context.h"
#include "image/metrics.h"
#include "reference/reference.h"
#include "render/debug_views.h"
#include "render/frame.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace py = pybind11;

namespace penumbra::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Bad settings, raised as ValueError with the message the command line prints after
// "penumbra: error: ".
[[noreturn]] void badArgument(const std::string& message) {
  throw py::value_error(message);
}

// One GL context for the process, made on first need: every renderer shares it.
std::shared_ptr<gl::HeadlessContext> sharedContext() {
  static std::weak_ptr<gl::HeadlessContext> shared;
  std::shared_ptr<gl::HeadlessContext> context = shared.lock();
  if (!context) {
    context = std::make_shared<gl::HeadlessContext>();
    shared = context;
  }
  return context;
}

// An H x W x 3 float32 array of an image's RGB (row 0 at the top).
FloatArray toArray(const Image& image) {
  FloatArray array({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width),
                    py::ssize_t{3}});
  float* out = array.mutable_data();
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      out[i * 3 + static_cast<std::size_t>(c)] = image.pixels[i][c];
  return array;
}

// An H x W x 3 or H x W x 4 array (linear values, row 0 at the top) as an image; alpha 1 for RGB.
Image toImage(const FloatArray& array, const std::string& what) {
  if (array.ndim() != 3 || (array.shape(2) != 3 && array.shape(2) != 4))
    badArgument(what + ": expected an array of shape (height, width, 3 or 4)");
  const auto channels = static_cast<std::size_t>(array.shape(2));
  Image image(static_cast<int>(array.shape(1)), static_cast<int>(array.shape(0)), glm::vec4(1.0f));
  const float* in = array.data();
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (std::size_t c = 0; c < channels; ++c)
      image.pixels[i][static_cast<int>(c)] = in[i * channels + c];
  return image;
}

glm::vec3 vec3Of(const py::handle& value) {
  const auto v = value.cast<std::vector<float>>();
  if (v.size() != 3)
    badArgument("expected 3 numbers, found " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

// An N x K array as N vectors of K components.
template <typename Vector, typename Scalar>
std::vector<Vector> rowsOf(const py::handle& value, const std::string& what) {
  const auto array = py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!array || array.ndim() != 2 || array.shape(1) != Vector::length())
    badArgument(what + ": expected an array of shape (N, " + std::to_string(Vector::length()) +
                ")");
  std::vector<Vector> rows(static_cast<std::size_t>(array.shape(0)));
  const Scalar* in = array.data();
  for (std::size_t row = 0; row < rows.size(); ++row)
    for (int c = 0; c < Vector::length(); ++c)
      rows[row][c] =
          in[row * static_cast<std::size_t>(Vector::length()) + static_cast<std::size_t>(c)];
  return rows;
}

template <typename T>
std::optional<T> optionalItem(const py::dict& dict, const char* key) {
  if (!dict.contains(key) || dict[key].is_none())
    return std::nullopt;
  return dict[key].cast<T>();
}

NormalsMode normalsModeOf(const std::string& name) {
  if (name == "file")
    return NormalsMode::File;
  if (name == "smooth")
    return NormalsMode::Smooth;
  if (name == "flat")
    return NormalsMode::Flat;
  badArgument("unknown normals mode '" + name + "', expected one of: file, smooth, flat");
}

MaterialDesc materialOf(const py::dict& item) {
  MaterialDesc material;
  material.name = item["name"].cast<std::string>();
  if (item.contains("ambient"))
    material.ambient = vec3Of(item["ambient"]);
  if (item.contains("diffuse"))
    material.diffuse = vec3Of(item["diffuse"]);
  if (item.contains("specular"))
    material.specular = vec3Of(item["specular"]);
  if (auto shininess = optionalItem<float>(item, "shininess"))
    material.shininess = *shininess;
  if (item.contains("emission") && !item["emission"].is_none())
    material.emission = vec3Of(item["emission"]);
  if (item.contains("texture") && !item["texture"].is_none()) {
    const py::object texture = item["texture"];
    if (py::isinstance<py::str>(texture) || py::hasattr(texture, "__fspath__"))
      material.texture = texture.cast<std::filesystem::path>();
    else
      material.textureImage = std::make_shared<const Image>(
          toImage(texture.cast<FloatArray>(), "material '" + material.name + "' texture"));
  }
  return material;
}

AreaLightDesc lightOf(const py::dict& item) {
  AreaLightDesc light;
  light.name = item["name"].cast<std::string>();
  const std::vector<glm::vec3> corners = rowsOf<glm::vec3, float>(item["corners"], "corners");
  if (corners.size() != 4)
    badArgument("area_light '" + light.name + "': expected 4 corners, found " +
                std::to_string(corners.size()));
  std::copy(corners.begin(), corners.end(), light.corners.begin());
  if (item.contains("at") && !item["at"].is_none())
    light.emittingSidePoint = vec3Of(item["at"]);
  light.material = item["material"].cast<std::string>();
  return light;
}

CameraDesc cameraOf(const py::dict& item) {
  CameraDesc camera;
  camera.name = optionalItem<std::string>(item, "name").value_or("camera");
  camera.position = vec3Of(item["position"]);
  camera.target = vec3Of(item["target"]);
  if (item.contains("up"))
    camera.up = vec3Of(item["up"]);
  camera.fovyDegrees = optionalItem<float>(item, "fovy").value_or(camera.fovyDegrees);
  camera.nearPlane = optionalItem<float>(item, "near").value_or(camera.nearPlane);
  camera.farPlane = optionalItem<float>(item, "far").value_or(camera.farPlane);
  if (auto size = optionalItem<std::pair<int, int>>(item, "size"))
    camera.screenSize = {size->first, size->second};
  return camera;
}

TransformStep transformStepOf(const py::handle& value) {
  const auto step = value.cast<py::tuple>();
  const auto kind = step[0].cast<std::string>();
  if (kind == "translate" && step.size() == 2)
    return {TransformStep::Kind::Translate, vec3Of(step[1])};
  if (kind == "rotate" && step.size() == 3)
    return {TransformStep::Kind::Rotate, vec3Of(step[2]), step[1].cast<float>()};
  if (kind == "scale" && step.size() == 2) {
    if (py::isinstance<py::float_>(step[1]) || py::isinstance<py::int_>(step[1]))
      return {TransformStep::Kind::Scale, glm::vec3(step[1].cast<float>())};
    return {TransformStep::Kind::Scale, vec3Of(step[1])};
  }
  badArgument(
      "transform steps are ('translate', xyz), ('rotate', degrees, axis) or "
      "('scale', factor or xyz)");
}

ObjectDesc objectOf(const py::dict& item, const SceneBuilder& builder) {
  ObjectDesc object;
  object.normals = normalsModeOf(optionalItem<std::string>(item, "normals").value_or("file"));
  if (item.contains("model")) {
    object.model = item["model"].cast<std::filesystem::path>();
  } else {
    MeshArrays mesh;
    mesh.name = optionalItem<std::string>(item, "name").value_or("mesh");
    mesh.positions = rowsOf<glm::vec3, float>(item["positions"], "positions");
    if (item.contains("normals_array"))
      mesh.normals = rowsOf<glm::vec3, float>(item["normals_array"], "normals_array");
    if (item.contains("uvs"))
      mesh.uvs = rowsOf<glm::vec2, float>(item["uvs"], "uvs");
    mesh.triangles = rowsOf<glm::uvec3, std::uint32_t>(item["triangles"], "triangles");
    object.mesh = makeMeshModel(mesh, object.normals, builder.origin());
  }
  if (item.contains("transform"))
    for (const py::handle step : item["transform"])
      object.transform.push_back(transformStepOf(step));
  object.material = optionalItem<std::string>(item, "material");
  return object;
}

// A loaded scene; renderers keep it alive.
struct PyScene {
  std::shared_ptr<Scene> scene;
  std::vector<std::string> warnings() const { return scene->warnings; }
  py::tuple size() const { return py::make_tuple(scene->camera.size.x, scene->camera.size.y); }
};

PyScene loadSceneFile(const std::filesystem::path& file) {
  return {std::make_shared<Scene>(loadScene(parseSceneFile(file)))};
}

PyScene buildScene(const py::list& materials, const py::list& lights,
                   const std::optional<py::dict>& camera, const py::list& objects,
                   const std::string& name) {
  SceneBuilder builder(name);
  for (const py::handle item : materials)
    builder.addMaterial(materialOf(item.cast<py::dict>()));
  for (const py::handle item : lights)
    builder.addLight(lightOf(item.cast<py::dict>()));
  if (camera)
    builder.setCamera(cameraOf(*camera));
  for (const py::handle item : objects)
    builder.addObject(objectOf(item.cast<py::dict>(), builder));
  return {std::make_shared<Scene>(loadScene(builder.finish()))};
}

template <typename Enum>
Enum choose(const std::string& option, const std::string& value,
            const std::vector<std::pair<std::string, Enum>>& choices) {
  std::string known;
  for (const auto& [name, choice] : choices) {
    if (name == value)
      return choice;
    known += (known.empty() ? "" : ", ") + name;
  }
  badArgument(option + ": unknown value '" + value + "', expected one of: " + known);
}

// The keyword arguments of a render, named as the command line's options with '_' for '-'.
struct RenderArguments {
  std::string mode = "hierarchical";
  int frame = 0;
  RenderSettings gpu;
  int spp = 256;
  std::uint64_t seed = 1;
  int bounces = 0;
  std::vector<std::string> aovs;
  bool statistics = false;

  bool onGpu() const { return mode == "hierarchical" || mode == "naive"; }

  RenderSettings gpuSettings() const {
    RenderSettings settings = gpu;
    settings.mode = mode == "naive" ? RenderMode::Naive : RenderMode::Hierarchical;
    return settings;
  }
};

RenderArguments argumentsOf(const py::kwargs& kwargs) {
  RenderArguments arguments;
  RenderSettings& gpu = arguments.gpu;
  VoxelSettings& voxels = gpu.shadows.voxels;
  for (const auto& [keyHandle, value] : kwargs) {
    const auto key = keyHandle.cast<std::string>();
    if (key == "mode")
      arguments.mode = value.cast<std::string>();
    else if (key == "frame")
      arguments.frame = value.cast<int>();
    else if (key == "vpls")
      gpu.vplsPerLight = value.cast<int>();
    else if (key == "coarsest")
      gpu.multiresolution.coarsestSize = value.cast<int>();
    else if (key == "depth_threshold")
      gpu.multiresolution.depthThreshold = value.cast<float>();
    else if (key == "normal_threshold")
      gpu.multiresolution.normalThreshold = value.cast<float>();
    else if (key == "plane_tolerance")
      gpu.multiresolution.planeTolerance = value.cast<float>();
    else if (key == "light_proximity_threshold")
      gpu.multiresolution.lightProximityThreshold = value.cast<float>();
    else if (key == "indirect")
      gpu.indirect.enabled = value.cast<bool>();
    else if (key == "indirect_vpls")
      gpu.indirect.vplCount = value.cast<int>();
    else if (key == "rsm_size")
      gpu.indirect.rsmSize = value.cast<int>();
    else if (key == "indirect_gather_size")
      gpu.indirect.gatherSize = value.cast<int>();
    else if (key == "indirect_plane_tolerance")
      gpu.indirect.planeTolerance = value.cast<float>();
    else if (key == "shadows")
      gpu.shadows.enabled = value.cast<bool>();
    else if (key == "visibility")
      gpu.shadows.visibility =
          choose<ShadowSettings::Visibility>(key, value.cast<std::string>(),
                                             {{"voxels", ShadowSettings::Visibility::Voxels},
                                              {"bvh", ShadowSettings::Visibility::Bvh}});
    else if (key == "voxel_grid")
      voxels.grid = choose<VoxelSettings::Grid>(
          key, value.cast<std::string>(),
          {{"world", VoxelSettings::Grid::World}, {"screen", VoxelSettings::Grid::Screen}});
    else if (key == "voxel_fill")
      voxels.fill = choose<VoxelSettings::Fill>(
          key, value.cast<std::string>(),
          {{"surface", VoxelSettings::Fill::Surface}, {"solid", VoxelSettings::Fill::Solid}});
    else if (key == "voxel_shape")
      voxels.shape = choose<VoxelSettings::Shape>(
          key, value.cast<std::string>(),
          {{"equal", VoxelSettings::Shape::Equal}, {"cubic", VoxelSettings::Shape::Cubic}});
    else if (key == "voxel_resolution")
      voxels.resolution = value.cast<int>();
    else if (key == "depth_slices")
      voxels.depthSlices = value.cast<int>();
    else if (key == "traversal")
      voxels.traversal = choose<VoxelSettings::Traversal>(
          key, value.cast<std::string>(),
          {{"dda", VoxelSettings::Traversal::Dda}, {"uniform", VoxelSettings::Traversal::Uniform}});
    else if (key == "ray_steps")
      voxels.steps = value.cast<int>();
    else if (key == "widen")
      voxels.widen = value.cast<bool>();
    else if (key == "voxel_boxes")
      voxels.boxes = value.cast<bool>();
    else if (key == "clear_light_test")
      gpu.shadows.clearLightTest = value.cast<bool>();
    else if (key == "shadow_offset")
      voxels.originOffset = value.cast<float>();
    else if (key == "visibility_measure")
      gpu.shadows.refinement.measure = choose<VisibilityRefinement::Measure>(
          key, value.cast<std::string>(),
          {{"xor", VisibilityRefinement::Measure::XorPopcount},
           {"count", VisibilityRefinement::Measure::OccludedCountDifference}});
    else if (key == "visibility_threshold")
      gpu.shadows.refinement.threshold = value.cast<float>();
    else if (key == "shared_vpls")
      gpu.shadows.refinement.shareVplsInBlocks = value.cast<bool>();
    else if (key == "visible_fraction")
      gpu.shadows.visibleFraction = value.cast<bool>();
    else if (key == "reuse_visibility")
      gpu.reuseVisibility = value.cast<bool>();
    else if (key == "spp")
      arguments.spp = value.cast<int>();
    else if (key == "seed")
      arguments.seed = value.cast<std::uint64_t>();
    else if (key == "bounces")
      arguments.bounces = value.cast<int>();
    else if (key == "aovs")
      arguments.aovs = value.cast<std::vector<std::string>>();
    else if (key == "statistics")
      arguments.statistics = value.cast<bool>();
    else
      badArgument("unknown keyword argument '" + key + "' (docs/python.md lists them)");
  }
  choose<int>("mode", arguments.mode,
              {{"hierarchical", 0}, {"naive", 0}, {"reference", 0}, {"reference-vpl", 0}});
  try {
    if (arguments.onGpu())
      validate(arguments.gpuSettings());
    else
      cellsPerSideFor(gpu.vplsPerLight);
  } catch (const RenderError& error) {
    badArgument(error.what());
  }
  if (arguments.spp < 1)
    badArgument("spp must be at least 1");
  if (arguments.bounces < 0 || arguments.bounces > 1)
    badArgument("bounces must be 0 or 1");
  if (arguments.bounces > 0 && arguments.onGpu())
    badArgument("bounces is for the reference modes; the GPU modes take indirect=True");
  if (!arguments.onGpu() && (!arguments.aovs.empty() || arguments.statistics))
    badArgument("aovs and statistics need a GPU mode (hierarchical or naive)");
  return arguments;
}

// A scene at one image size, with its GPU renderer made on the first GPU frame. One thread at a
// time: the GL context is current on the thread that made it.
class PyRenderer {
 public:
  PyRenderer(PyScene scene, std::optional<std::pair<int, int>> size) : scene_(std::move(scene)) {
    size_ = size ? glm::ivec2(size->first, size->second) : scene_.scene->camera.size;
    if (size_.x <= 0 || size_.y <= 0)
      badArgument("size: expected positive WIDTH and HEIGHT");
    if (scene_.scene->lights.empty())
      badArgument(scene_.scene->file.string() +
                  ": error: the scene has no area_light, so nothing would be lit; add an "
                  "area_light block (docs/scene-format.md)");
  }

  // The radiance alone, or with aovs/statistics a dict of them.
  py::object render(const py::kwargs& kwargs) {
    const RenderArguments arguments = argumentsOf(kwargs);
    if (!arguments.onGpu())
      return toArray(renderOnCpu(arguments));
    Image radiance;
    std::vector<Image> aovs;
    FrameStatistics statistics;
    const RenderSettings settings = arguments.gpuSettings();
    {
      const py::gil_scoped_release unlocked;
      if (!renderer_) {
        context_ = sharedContext();
        renderer_ = std::make_unique<Renderer>(*scene_.scene, size_);
      }
      renderer_->render(arguments.frame, settings);
      radiance = renderer_->readRadiance();
      for (const std::string& aov : arguments.aovs)
        aovs.push_back(debugView(*renderer_, aov, settings));
      if (arguments.statistics)
        statistics = renderer_->statistics();
    }
    if (arguments.aovs.empty() && !arguments.statistics)
      return toArray(radiance);
    py::dict result;
    result["radiance"] = toArray(radiance);
    for (std::size_t index = 0; index < aovs.size(); ++index)
      result[py::str(arguments.aovs[index])] = toArray(aovs[index]);
    if (arguments.statistics)
      result["statistics"] = py::module_::import("json").attr("loads")(
          app::statisticsJson(statistics, settings).dump());
    return result;
  }

 private:
  Image renderOnCpu(const RenderArguments& arguments) const {
    ReferenceSettings settings;
    settings.sampling = arguments.mode == "reference" ? ReferenceSettings::Sampling::Stratified
                                                      : ReferenceSettings::Sampling::Vpl;
    settings.samplesPerPixel = arguments.spp;
    settings.vplsPerLight = arguments.gpu.vplsPerLight;
    settings.seed = arguments.seed;
    settings.shadows = arguments.gpu.shadows.enabled;
    settings.bounces = arguments.bounces;
    settings.frame = arguments.frame;
    settings.size = size_;
    const py::gil_scoped_release unlocked;
    return renderReference(*scene_.scene, settings);
  }

  PyScene scene_;
  glm::ivec2 size_{0};
  std::shared_ptr<gl::HeadlessContext> context_;
  std::unique_ptr<Renderer> renderer_;
};

py::dict compare(const FloatArray& a, const FloatArray& b) {
  ImageMetrics metrics;
  try {
    metrics = compareImages(toImage(a, "a"), toImage(b, "b"));
  } catch (const ImageError& error) {
    badArgument(error.what());
  }
  py::dict result;
  result["rmse"] = metrics.rmse;
  result["relmse"] = metrics.relativeMse;
  result["psnr"] = metrics.psnr;
  result["mae"] = metrics.mae;
  result["max"] = metrics.maxError;
  return result;
}

}  // namespace
}  // namespace penumbra::python

PYBIND11_MODULE(penumbra, module) {
  using namespace penumbra;
  using namespace penumbra::python;
  module.doc() = "Penumbra: multiresolution area-light rendering (docs/python.md)";
  py::register_exception<SceneError>(module, "SceneError", PyExc_ValueError);
  py::register_exception<gl::ContextError>(module, "GpuError", PyExc_RuntimeError);
  py::register_exception<RenderError>(module, "RenderError", PyExc_ValueError);
  py::register_exception<ImageError>(module, "ImageError", PyExc_OSError);

  py::class_<PyScene>(module, "Scene", "A loaded scene")
      .def_property_readonly("warnings", &PyScene::warnings)
      .def_property_readonly("size", &PyScene::size, "The camera's (width, height)");
  module.def("load_scene", &loadSceneFile, py::arg("path"), "Loads a scene file");
  module.def("build_scene", &buildScene, py::kw_only(), py::arg("materials") = py::list(),
             py::arg("lights") = py::list(), py::arg("camera") = std::nullopt,
             py::arg("objects") = py::list(), py::arg("name") = "in-memory scene",
             "Builds a scene from dicts and NumPy arrays, with the scene file's checks");

  py::class_<PyRenderer>(module, "Renderer", "A scene at one image size, for many frames")
      .def(py::init<PyScene, std::optional<std::pair<int, int>>>(), py::arg("scene"),
           py::arg("size") = std::nullopt)
      .def("render", &PyRenderer::render,
           "Renders a frame: the radiance as a (height, width, 3) float32 array, or with aovs or "
           "statistics=True a dict of them");
  module.def(
      "render",
      [](const PyScene& scene, std::optional<std::pair<int, int>> size, const py::kwargs& kwargs) {
        return PyRenderer(scene, size).render(kwargs);
      },
      py::arg("scene"), py::arg("size") = std::nullopt, "Renders one frame of a scene");
  module.def("compare", &compare, py::arg("a"), py::arg("b"),
             "Metrics of image a against the reference b, as `penumbra compare` prints them");
}
