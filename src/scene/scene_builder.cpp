#include "scene/scene_builder.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "scene/area_light.h"
#include "scene/tokenizer.h"
#include "scene/transform.h"

namespace penumbra {

std::optional<ValueSite> ValueSites::find(std::string_view, std::size_t, std::size_t) const {
  return std::nullopt;
}

namespace {

// Paths in full: the user needs the whole of them to find the file.
std::string formatNumber(float value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Why `path` is no file to read ("" when it is one), for "model file 'x' ..." messages.
std::string fileProblem(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_regular_file(path, error))
    return {};
  if (std::filesystem::is_directory(path, error))
    return "is a directory (looked at " + quotePath(path) + ")";
  return "not found (looked for " + quotePath(path) + ")";
}

// The checks of one block: each failure is located at the token the sites name, or at the block.
class BlockChecks {
 public:
  BlockChecks(const ValueSites& sites, const SourceLocation& block)
      : sites_(sites), block_(block) {}

  ValueSite site(std::string_view key, std::size_t index, const std::string& text,
                 std::size_t occurrence = ValueSites::kLast) const {
    if (std::optional<ValueSite> found = sites_.find(key, index, occurrence))
      return *std::move(found);
    return {block_, text};
  }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw SceneError(where, message);
  }

  void finite(std::string_view key, std::size_t index, float value,
              std::size_t occurrence = ValueSites::kLast) const {
    if (!std::isfinite(value)) {
      const ValueSite at = site(key, index, formatNumber(value), occurrence);
      fail(at.where, expectedFiniteNumber(at.text));
    }
  }

  // `first` is the token index of the vector's first component.
  void finite(std::string_view key, std::size_t first, glm::vec3 value,
              std::size_t occurrence = ValueSites::kLast) const {
    for (int component = 0; component < 3; ++component)
      finite(key, first + static_cast<std::size_t>(component), value[component], occurrence);
  }

  // "'KEY' REQUIREMENT, found 'VALUE'" when `inRange` is false.
  void range(std::string_view key, std::size_t index, float value, bool inRange,
             std::string_view requirement, std::size_t occurrence = ValueSites::kLast) const {
    if (inRange)
      return;
    const ValueSite at = site(key, index, formatNumber(value), occurrence);
    fail(at.where,
         quoteToken(key) + " " + std::string(requirement) + ", found " + quoteToken(at.text));
  }

  // A colour whose components must lie in [0, 1] (`dif`, `spec`).
  void unitColor(std::string_view key, glm::vec3 color) const {
    finite(key, 1, color);
    for (int component = 0; component < 3; ++component)
      range(key, static_cast<std::size_t>(component) + 1, color[component],
            color[component] >= 0.0f && color[component] <= 1.0f, "values must be in [0, 1]");
  }

  // A file the block names (`key` statement's value, or the header's path for key "").
  void fileExists(std::string_view key, std::string_view noun,
                  const std::filesystem::path& file) const {
    const std::string problem = fileProblem(file);
    if (problem.empty())
      return;
    const ValueSite at = site(key, 1, file.string());
    fail(at.where, std::string(noun) + " file " + quotePath(at.text) + " " + problem);
  }

  void uniqueName(std::map<std::string, SourceLocation>& seen, std::string_view kind,
                  const std::string& name) const {
    const auto [existing, inserted] = seen.emplace(name, block_);
    if (!inserted)
      fail(site("", 1, name).where, "duplicate " + std::string(kind) + " name " + quoteToken(name) +
                                        ", first defined at " + existing->second.str());
  }

  const SourceLocation& block() const { return block_; }

 private:
  const ValueSites& sites_;
  SourceLocation block_;
};

void locateAt(SourceLocation& where, const SourceLocation& origin) {
  if (where.file.empty())
    where = origin;
}

// The k-th statement of each transform kind, as the parser counts them.
const char* transformKey(TransformStep::Kind kind) {
  switch (kind) {
    case TransformStep::Kind::Translate:
      return "translate";
    case TransformStep::Kind::Rotate:
      return "rotate";
    case TransformStep::Kind::Scale:
      return "scale";
  }
  return "";
}

}  // namespace

std::shared_ptr<const Model> makeMeshModel(const MeshArrays& arrays, NormalsMode normals,
                                           const SourceLocation& where) {
  const std::string name = "mesh " + quoteToken(arrays.name) + ": ";
  const auto fail = [&](const std::string& problem) { throw SceneError(where, name + problem); };
  const std::size_t count = arrays.positions.size();
  if (arrays.triangles.empty())
    fail("has no triangles");
  if (!arrays.normals.empty() && arrays.normals.size() != count)
    fail(std::to_string(arrays.normals.size()) + " normals for " + std::to_string(count) +
         " positions; give one per position or none");
  if (!arrays.uvs.empty() && arrays.uvs.size() != count)
    fail(std::to_string(arrays.uvs.size()) + " uvs for " + std::to_string(count) +
         " positions; give one per position or none");
  for (std::size_t v = 0; v < count; ++v) {
    const std::string vertex = "vertex " + std::to_string(v);
    const glm::vec3& p = arrays.positions[v];
    std::string problem = nonFiniteVertexProblem(vertex, "position", {p.x, p.y, p.z});
    if (problem.empty() && !arrays.normals.empty()) {
      const glm::vec3& n = arrays.normals[v];
      problem = nonFiniteVertexProblem(vertex, "normal", {n.x, n.y, n.z});
    }
    if (problem.empty() && !arrays.uvs.empty())
      problem =
          nonFiniteVertexProblem(vertex, "texture coordinate", {arrays.uvs[v].x, arrays.uvs[v].y});
    if (!problem.empty())
      fail(problem);
  }
  for (std::size_t t = 0; t < arrays.triangles.size(); ++t)
    for (int corner = 0; corner < 3; ++corner)
      if (arrays.triangles[t][corner] >= count)
        fail("triangle " + std::to_string(t) + " uses vertex " +
             std::to_string(arrays.triangles[t][corner]) + ", but there are " +
             std::to_string(count) + " positions");

  Mesh mesh;
  mesh.positions = arrays.positions;
  mesh.normals = arrays.normals;
  mesh.uvs = arrays.uvs.empty() ? std::vector<glm::vec2>(count, glm::vec2(0.0f)) : arrays.uvs;
  mesh.triangles = arrays.triangles;
  auto model = std::make_shared<Model>();
  model->meshes.push_back(std::move(mesh));
  chooseNormals(*model, normals);
  return model;
}

SceneBuilder::SceneBuilder(std::filesystem::path origin) {
  scene_.file = std::move(origin);
}

SourceLocation SceneBuilder::origin() const {
  return {scene_.file.string(), 0, 0};
}

void SceneBuilder::addMaterial(MaterialDesc material, const ValueSites& sites) {
  locateAt(material.where, origin());
  const BlockChecks checks(sites, material.where);
  checks.uniqueName(materialNames_, "material", material.name);
  checks.finite("amb", 1, material.ambient);
  checks.unitColor("dif", material.diffuse);
  checks.unitColor("spec", material.specular);
  checks.finite("shin", 1, material.shininess);
  checks.range("shin", 1, material.shininess, material.shininess >= 0.0f, "must be >= 0");
  if (material.emission) {
    checks.finite("emit", 1, *material.emission);
    for (int component = 0; component < 3; ++component)
      checks.range("emit", static_cast<std::size_t>(component) + 1, (*material.emission)[component],
                   (*material.emission)[component] >= 0.0f, "values must be >= 0");
  }
  if (material.texture) {
    checks.fileExists("tex", "texture", *material.texture);
    // Texture errors found when the scene loads (a damaged image) point at the `tex` value.
    if (std::optional<ValueSite> value = sites.find("tex", 1, ValueSites::kLast))
      material.textureWhere = value->where;
    locateAt(material.textureWhere, material.where);
  }
  if (material.emissionTexture)
    checks.fileExists("emit_tex", "emission texture", *material.emissionTexture);
  // Without `emit` the material lights nothing, so its emission keys would be silently unused.
  if (!material.emission && (material.emissionTexture || material.emissionTextureImage))
    checks.fail(checks.site("emit_tex", 1, "").where,
                "material " + quoteToken(material.name) +
                    ": 'emit_tex' needs 'emit' (the radiance the texture scales)");
  if (!material.emission && material.twoSided)
    checks.fail(checks.site("two_sided", 1, "").where,
                "material " + quoteToken(material.name) + ": 'two_sided' needs 'emit'");
  const auto checkImage = [&](const std::shared_ptr<const Image>& image, std::string_view noun) {
    if (image && (image->width <= 0 || image->height <= 0 ||
                  image->pixels.size() != static_cast<std::size_t>(image->width) * image->height))
      checks.fail(material.where, "material " + quoteToken(material.name) + ": the " +
                                      std::string(noun) +
                                      " image has no pixels or the wrong number");
  };
  checkImage(material.textureImage, "texture");
  checkImage(material.emissionTextureImage, "emission texture");
  scene_.materials.push_back(std::move(material));
}

void SceneBuilder::addLight(AreaLightDesc light, const ValueSites& sites) {
  locateAt(light.where, origin());
  locateAt(light.materialWhere, light.where);
  const BlockChecks checks(sites, light.where);
  checks.uniqueName(lightNames_, "area_light", light.name);
  for (std::size_t corner = 0; corner < 4; ++corner)
    checks.finite("pos" + std::to_string(corner + 1), 1, light.corners[corner]);
  if (light.emittingSidePoint)
    checks.finite("at", 1, *light.emittingSidePoint);
  std::string problem;
  if (!makeQuadLight(light.corners, light.emittingSidePoint, problem))
    checks.fail(light.where, "area_light " + quoteToken(light.name) + ": " + problem);
  references_.push_back({light.material, light.materialWhere});
  scene_.lights.push_back(std::move(light));
}

void SceneBuilder::setCamera(CameraDesc camera, const ValueSites& sites) {
  locateAt(camera.where, origin());
  const BlockChecks checks(sites, camera.where);
  if (scene_.camera)
    checks.fail(camera.where, "a second camera " + quoteToken(camera.name) +
                                  ": only one camera is allowed, " +
                                  quoteToken(scene_.camera->name) + " is defined at " +
                                  scene_.camera->where.str());
  checks.finite("pos", 1, camera.position);
  checks.finite("at", 1, camera.target);
  checks.finite("up", 1, camera.up);
  checks.finite("fovy", 1, camera.fovyDegrees);
  checks.range("fovy", 1, camera.fovyDegrees,
               camera.fovyDegrees > 0.0f && camera.fovyDegrees < 180.0f,
               "must be in (0, 180) degrees");
  checks.finite("near", 1, camera.nearPlane);
  checks.range("near", 1, camera.nearPlane, camera.nearPlane > 0.0f, "must be > 0");
  checks.finite("far", 1, camera.farPlane);
  checks.range("far", 1, camera.farPlane, camera.farPlane > 0.0f, "must be > 0");
  for (int axis = 0; axis < 2; ++axis) {
    if (camera.screenSize[axis] <= 0) {
      const ValueSite at = checks.site("screen_size", static_cast<std::size_t>(axis) + 1,
                                       std::to_string(camera.screenSize[axis]));
      checks.fail(at.where, expectedPositiveInteger(at.text));
    }
  }
  if (camera.nearPlane >= camera.farPlane) {
    // The value written last is the one to change; `far` when both are written.
    const bool farWritten = sites.find("far", 1, ValueSites::kLast).has_value();
    const std::string culprit = farWritten ? "far" : "near";
    const float value = farWritten ? camera.farPlane : camera.nearPlane;
    checks.fail(checks.site(culprit, 1, formatNumber(value)).where,
                "'near' (" + formatNumber(camera.nearPlane) + ") must be less than 'far' (" +
                    formatNumber(camera.farPlane) + ")");
  }
  // gluLookAt has no orientation for these; the image would be all NaN.
  const glm::vec3 viewDirection = camera.target - camera.position;
  if (viewDirection == glm::vec3(0.0f))
    checks.fail(camera.where,
                "camera " + quoteToken(camera.name) + ": 'pos' and 'at' are the same point");
  // Nearly parallel is as bad: the basis then follows float rounding. The limit is the sine
  // of the angle between them, far above the rounding of the unit vectors (about 1e-7).
  constexpr float kLeastSine = 1e-4f;
  const float upLength = glm::length(camera.up);
  if (!(upLength > 0.0f) ||
      glm::length(glm::cross(glm::normalize(viewDirection), camera.up / upLength)) < kLeastSine)
    checks.fail(checks.site("up", 1, formatNumber(camera.up.x)).where,
                "camera " + quoteToken(camera.name) +
                    ": 'up' is zero or parallel to the viewing direction");
  scene_.camera = std::move(camera);
}

void SceneBuilder::addObject(ObjectDesc object, const ValueSites& sites) {
  locateAt(object.where, origin());
  locateAt(object.materialWhere, object.where);
  const BlockChecks checks(sites, object.where);
  if (!object.mesh)
    checks.fileExists("", "model", object.model);
  std::map<std::string, std::size_t> occurrences;
  object.staticTransform = glm::mat4(1.0f);
  for (const TransformStep& step : object.transform) {
    const std::string key = transformKey(step.kind);
    const std::size_t occurrence = occurrences[key]++;
    switch (step.kind) {
      case TransformStep::Kind::Translate:
        checks.finite(key, 1, step.vector, occurrence);
        object.staticTransform *= translationMatrix(step.vector);
        break;
      case TransformStep::Kind::Rotate:
        checks.finite(key, 1, step.angleDegrees, occurrence);
        checks.finite(key, 2, step.vector, occurrence);
        if (step.vector == glm::vec3(0.0f))
          checks.fail(checks.site(key, 2, "0", occurrence).where,
                      "the rotation axis must not be zero");
        object.staticTransform *= rotationMatrix(step.angleDegrees, step.vector);
        break;
      case TransformStep::Kind::Scale:
        checks.finite(key, 1, step.vector, occurrence);
        // A zero factor flattens the model and leaves its normals undefined.
        for (int component = 0; component < 3; ++component)
          checks.range(key, static_cast<std::size_t>(component) + 1, step.vector[component],
                       step.vector[component] != 0.0f, "factors must not be zero", occurrence);
        object.staticTransform *= scaleMatrix(step.vector);
        break;
    }
  }
  for (std::size_t index = 0; index < object.animations.size(); ++index) {
    const Animation& animation = object.animations[index];
    checks.finite("anim", 2, animation.axis, index);
    checks.finite("anim", 5, animation.step, index);
    if (animation.kind == Animation::Kind::Rotate && animation.axis == glm::vec3(0.0f))
      checks.fail(checks.site("anim", 2, "0", index).where, "the rotation axis must not be zero");
  }
  if (object.material)
    references_.push_back({*object.material, object.materialWhere});
  scene_.objects.push_back(std::move(object));
}

bool SceneBuilder::hasMaterial(const std::string& name) const {
  return materialNames_.contains(name);
}

bool SceneBuilder::hasCamera() const {
  return scene_.camera.has_value();
}

void SceneBuilder::addWarning(std::string warning) {
  scene_.warnings.push_back(std::move(warning));
}

SceneDesc SceneBuilder::finish() {
  for (const MaterialReference& reference : references_)
    if (scene_.findMaterial(reference.name) == nullptr)
      throw SceneError(reference.where, "undefined material " + quoteToken(reference.name) +
                                            ": no material block has this name");
  return std::move(scene_);
}

}  // namespace penumbra
