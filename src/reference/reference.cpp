#include "reference/reference.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <glm/gtc/constants.hpp>

#include "reference/ray_scene.h"
#include "scene/mesh_light.h"
#include "scene/shadow_terminator.h"
#include "scene/transform.h"

namespace penumbra {
namespace {

constexpr float kPi = glm::pi<float>();
constexpr int kTileSize = 16;

// Counter-based random numbers: a sample's jitter is a hash of (seed, pixel, light, sample), so the
// image depends on the seed alone and never on which thread rendered which tile.
std::uint64_t splitMix64(std::uint64_t value) {
  value += 0x9E3779B97F4A7C15ull;
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ull;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBull;
  return value ^ (value >> 31);
}

glm::vec2 sampleJitter(std::uint64_t seed, std::uint64_t pixel, std::uint64_t light,
                       std::uint64_t sample) {
  std::uint64_t state = splitMix64(seed);
  state = splitMix64(state ^ pixel);
  state = splitMix64(state ^ light);
  state = splitMix64(state ^ sample);
  // Two 24-bit fractions, exact in a float and strictly below 1.
  constexpr float kUnit = 1.0f / 16777216.0f;
  return {static_cast<float>(state >> 40) * kUnit,
          static_cast<float>((state >> 16) & 0xFFFFFFu) * kUnit};
}

int strataPerSide(int samplesPerPixel) {
  int side = 1;
  while (side * side < samplesPerPixel) {
    ++side;
  }
  return side;
}

int vplsPerSide(int vplsPerLight) {
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(vplsPerLight))));
  if (vplsPerLight < 1 || side * side != vplsPerLight) {
    throw std::invalid_argument("VPLs per light must be a perfect square (16, 64, 256, ...), got " +
                                std::to_string(vplsPerLight));
  }
  return side;
}

glm::ivec2 outputSize(const Scene& scene, const ReferenceSettings& settings) {
  if (settings.size == glm::ivec2(0)) {
    return scene.camera.size;
  }
  if (settings.size.x < 1 || settings.size.y < 1) {
    throw std::invalid_argument("image size must be positive, got " +
                                std::to_string(settings.size.x) + "x" +
                                std::to_string(settings.size.y));
  }
  return settings.size;
}

// |dP/du x dP/dv| of the light's bilinear map P(u,v) (QuadLight::pointAt): the area a sample
// cell of unit (u,v) area covers there. Constant (the quad's area) for a parallelogram.
float bilinearJacobian(const QuadLight& quad, glm::vec2 uv) {
  const auto& c = quad.corners;
  const glm::vec3 alongU = (1.0f - uv.y) * (c[1] - c[0]) + uv.y * (c[2] - c[3]);
  const glm::vec3 alongV = (1.0f - uv.x) * (c[3] - c[0]) + uv.x * (c[2] - c[1]);
  return glm::length(glm::cross(alongU, alongV));
}

struct SurfacePoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};      // interpolated, unit, on the side the surface is seen from
  glm::vec3 faceNormal{0.0f};  // the triangle's, unit, on the viewer's side
  glm::vec3 shadowRayOrigin{0.0f};
  glm::vec3 toViewer{0.0f};
  glm::vec3 albedo{0.0f};
  glm::vec3 specular{0.0f};
  float shininess = 1.0f;
  glm::vec3 ambient{0.0f};
};

// Diffuse plus normalised Phong, for light arriving from direction `toLight`.
glm::vec3 reflectance(const SurfacePoint& point, glm::vec3 toLight) {
  const glm::vec3 diffuse = point.albedo / kPi;
  if (point.specular == glm::vec3(0.0f)) {
    return diffuse;  // most surfaces: spares a pow per light sample
  }
  const float mirrorCosine =
      std::max(0.0f, glm::dot(glm::reflect(-toLight, point.normal), point.toViewer));
  return diffuse + point.specular * ((point.shininess + 2.0f) / (2.0f * kPi) *
                                     std::pow(mirrorCosine, point.shininess));
}

struct LightSource {
  const Light* light = nullptr;
  const Image* texture = nullptr;  // the frame at the render's scene time; nullptr: T = 1
  std::vector<Vpl> vpls;           // Sampling::Vpl only
  // A mesh light's triangles at the frame, and its samples by area.
  std::unique_ptr<MeshLightGeometry> mesh;
  std::optional<MeshLightSampler> meshSampler;
};

// A point on a light for sample coordinates u in [0,1)^2, with its density's inverse (the area
// the sample stands for, at unit sample measure).
struct LightPoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};  // on the emitting side; a two-sided light's is turned to the receiver
  glm::vec3 emission{0.0f};
  float jacobian = 0.0f;
};

LightPoint lightPoint(const LightSource& source, glm::vec2 u, glm::vec3 receiver) {
  LightPoint point;
  glm::vec2 uv = u;
  if (source.meshSampler) {
    const SurfaceSample sample = source.meshSampler->sample(u);
    point.position = sample.position;
    point.normal = sample.normal;
    point.jacobian = source.meshSampler->area();
    uv = sample.uv;
    if (source.light->twoSided && glm::dot(point.normal, receiver - point.position) < 0.0f)
      point.normal = -point.normal;
  } else {
    const QuadLight& quad = source.light->quad;
    point.position = quad.pointAt(uv);
    point.normal = quad.normal;
    point.jacobian = bilinearJacobian(quad, uv);
  }
  point.emission = source.light->emission;
  if (source.texture != nullptr)
    point.emission *= glm::vec3(sampleBilinear(*source.texture, uv, Wrap::ClampToEdge));
  return point;
}

class PixelRenderer {
 public:
  PixelRenderer(const Scene& scene, const ReferenceSettings& settings,
                const FrameGeometry& geometry, const RayScene& rays, const Camera& camera)
      : scene_(scene), settings_(settings), geometry_(geometry), rays_(rays), camera_(camera) {
    const double seconds = sceneTime(settings.frame);
    for (const auto& texture : scene.textures) {
      textureFrames_.push_back(&texture->frameAt(seconds));
    }
    if (settings.bounces < 0 || settings.bounces > 1) {
      throw std::invalid_argument("bounces must be 0 or 1, got " +
                                  std::to_string(settings.bounces));
    }
    if (settings.bounces > 0 && settings.samplesPerPixel < 1) {
      throw std::invalid_argument("samples per pixel must be at least 1, got " +
                                  std::to_string(settings.samplesPerPixel));
    }
    if (settings.sampling == ReferenceSettings::Sampling::Stratified) {
      if (settings.samplesPerPixel < 1) {
        throw std::invalid_argument("samples per pixel must be at least 1, got " +
                                    std::to_string(settings.samplesPerPixel));
      }
      strataPerSide_ = strataPerSide(settings.samplesPerPixel);
    }
    const int cellsPerSide = settings.sampling == ReferenceSettings::Sampling::Vpl
                                 ? vplsPerSide(settings.vplsPerLight)
                                 : 0;
    for (const Light& light : scene.lights) {
      LightSource& source = lights_.emplace_back();
      source.light = &light;
      source.texture = textureFrame(light.texture);
      if (light.isMesh()) {
        source.mesh =
            std::make_unique<MeshLightGeometry>(meshLightGeometry(scene, light, settings.frame));
        source.meshSampler.emplace(*source.mesh);
      }
      if (cellsPerSide > 0) {
        source.vpls = light.isMesh()
                          ? makeMeshVpls(*source.mesh, light.emission, source.texture,
                                         light.twoSided, cellsPerSide * cellsPerSide)
                          : makeVpls(light.quad, light.emission, source.texture, cellsPerSide);
      }
    }
    // Hit points carry float rounding error of about 1e-7 of the scene's extent, so shadow rays
    // start 1e-4 of its diagonal off the surface: far above that error (no self-shadowing acne),
    // far below any gap the scenes are meant to resolve (contact shadows survive).
    shadowRayOffset_ = 1e-4f * glm::length(geometry.boundsMax - geometry.boundsMin);
  }

  glm::vec3 pixel(int x, int y, std::uint64_t& raysTraced) const {
    const glm::vec3 direction = camera_.rayDirection(x, y);
    const RayHit hit = traceCameraRay(rays_, camera_, direction);
    ++raysTraced;
    switch (hit.kind) {
      case RayHit::Kind::Nothing:
        return glm::vec3(0.0f);
      case RayHit::Kind::Light:
        return emitted(hit, direction);
      case RayHit::Kind::Surface:
        break;
    }
    if (const SurfaceMaterial& material = materialOf(hit); material.emits) {
      return meshEmission(hit, material, direction);
    }
    const SurfacePoint point = surfacePoint(hit, direction);
    const auto pixelIndex = static_cast<std::uint64_t>(y) * camera_.size.x + x;
    glm::vec3 radiance = point.ambient;
    for (std::size_t light = 0; light < lights_.size(); ++light) {
      radiance += settings_.sampling == ReferenceSettings::Sampling::Stratified
                      ? stratifiedLight(point, lights_[light], pixelIndex, light, raysTraced)
                      : vplLight(point, lights_[light], raysTraced);
    }
    if (settings_.bounces >= 1) {
      radiance += oneBounce(point, pixelIndex, raysTraced);
    }
    return radiance;
  }

 private:
  const Image* textureFrame(int texture) const {
    return texture < 0 ? nullptr : textureFrames_[static_cast<std::size_t>(texture)];
  }

  glm::vec3 emitted(const RayHit& hit, glm::vec3 direction) const {
    const LightSource& source = lights_[static_cast<std::size_t>(hit.index)];
    const QuadLight& quad = source.light->quad;
    if (glm::dot(quad.normal, -direction) <= 0.0f) {
      return glm::vec3(0.0f);
    }
    if (source.texture == nullptr) {
      return source.light->emission;
    }
    // The hit's (u,v) on the quad, and the same from the triangle's corners as a fallback for a
    // hit on the quad's border that rounding puts a hair outside it.
    const glm::vec2 b = hit.barycentric;
    const auto& c = quad.corners;
    glm::vec3 point;
    glm::vec2 triangleUv;
    if (hit.lightTriangle == 0) {
      point = (1.0f - b.x - b.y) * c[0] + b.x * c[1] + b.y * c[2];
      triangleUv = {b.x + b.y, b.y};
    } else {
      point = (1.0f - b.x - b.y) * c[0] + b.x * c[2] + b.y * c[3];
      triangleUv = {b.x, b.x + b.y};
    }
    const glm::vec2 uv =
        quad.uvAt(point).value_or(glm::clamp(triangleUv, glm::vec2(0.0f), glm::vec2(1.0f)));
    return source.light->emission *
           glm::vec3(sampleBilinear(*source.texture, uv, Wrap::ClampToEdge));
  }

  const SurfaceMaterial& materialOf(const RayHit& hit) const {
    return scene_.materials[static_cast<std::size_t>(
        geometry_.triangleMaterial[static_cast<std::size_t>(hit.index)])];
  }

  // What a mesh light's surface shows: E T(uv) on its emitting side (both for a two-sided one),
  // the side its interpolated normal faces, as the G-buffer decides.
  glm::vec3 meshEmission(const RayHit& hit, const SurfaceMaterial& material,
                         glm::vec3 direction) const {
    const glm::uvec3 triangle = geometry_.triangles[static_cast<std::size_t>(hit.index)];
    const float w1 = hit.barycentric.x;
    const float w2 = hit.barycentric.y;
    const float w0 = 1.0f - w1 - w2;
    const glm::vec3 normal = w0 * geometry_.normals[triangle.x] +
                             w1 * geometry_.normals[triangle.y] +
                             w2 * geometry_.normals[triangle.z];
    if (!material.twoSided && glm::dot(normal, -direction) <= 0.0f) {
      return glm::vec3(0.0f);
    }
    glm::vec3 emission = material.emission;
    if (const Image* texture = textureFrame(material.emissionTexture)) {
      const glm::vec2 uv = w0 * geometry_.uvs[triangle.x] + w1 * geometry_.uvs[triangle.y] +
                           w2 * geometry_.uvs[triangle.z];
      emission *= glm::vec3(sampleBilinear(*texture, uv, Wrap::ClampToEdge));
    }
    return emission;
  }

  SurfacePoint surfacePoint(const RayHit& hit, glm::vec3 direction) const {
    const auto triangleIndex = static_cast<std::size_t>(hit.index);
    const glm::uvec3 triangle = geometry_.triangles[triangleIndex];
    const float w1 = hit.barycentric.x;
    const float w2 = hit.barycentric.y;
    const float w0 = 1.0f - w1 - w2;
    const auto& positions = geometry_.positions;
    const auto& normals = geometry_.normals;

    SurfacePoint point;
    point.toViewer = -direction;
    point.position =
        w0 * positions[triangle.x] + w1 * positions[triangle.y] + w2 * positions[triangle.z];
    glm::vec3 faceNormal = glm::cross(positions[triangle.y] - positions[triangle.x],
                                      positions[triangle.z] - positions[triangle.x]);
    faceNormal = glm::dot(faceNormal, point.toViewer) < 0.0f ? -faceNormal : faceNormal;
    faceNormal = glm::normalize(faceNormal);
    point.faceNormal = faceNormal;
    const glm::vec3 interpolated =
        w0 * normals[triangle.x] + w1 * normals[triangle.y] + w2 * normals[triangle.z];
    point.normal =
        glm::dot(interpolated, interpolated) > 0.0f ? glm::normalize(interpolated) : faceNormal;
    // Two-sided surfaces (docs/scene-format.md): a surface seen from behind, the viewer on the
    // other side of the face from where its normal points, is shaded with the normal flipped.
    // The face decides, not the angle to the viewer: a smooth normal that leans away from a
    // grazing viewer on the front side still faces the side the viewer is on.
    const float side = glm::dot(point.normal, faceNormal) < 0.0f ? -1.0f : 1.0f;
    point.normal *= side;
    // Off the surface along the face normal, not the interpolated one: on a coarse mesh of a
    // curved surface the interpolated normal can lean through the face, which would start the
    // shadow ray on the surface's far side. And from the point lifted onto the curved surface
    // the normals describe, not from the flat triangle (Hanika 2021, "Hacking the shadow
    // terminator"): where the smooth normal turns to a light that the face itself turns from,
    // a ray from the flat face would hit the neighbouring faces of the same convex mesh and
    // draw the mesh's polygons into the terminator.
    const std::array<glm::vec3, 3> corners{positions[triangle.x], positions[triangle.y],
                                           positions[triangle.z]};
    const std::array<glm::vec3, 3> cornerNormals{normals[triangle.x], normals[triangle.y],
                                                 normals[triangle.z]};
    point.shadowRayOrigin =
        liftedOntoNormals(point.position, corners, cornerNormals, {w0, w1, w2}, side) +
        shadowRayOffset_ * faceNormal;

    const SurfaceMaterial& material =
        scene_.materials[static_cast<std::size_t>(geometry_.triangleMaterial[triangleIndex])];
    point.albedo = material.diffuse;
    if (const Image* texture = textureFrame(material.texture)) {
      const glm::vec2 uv = w0 * geometry_.uvs[triangle.x] + w1 * geometry_.uvs[triangle.y] +
                           w2 * geometry_.uvs[triangle.z];
      point.albedo *= glm::vec3(sampleBilinear(*texture, uv, Wrap::Repeat));
    }
    point.specular = material.specular;
    point.shininess = material.shininess;
    point.ambient = material.ambient;
    return point;
  }

  bool visible(const SurfacePoint& point, glm::vec3 lightPoint, std::uint64_t& raysTraced) const {
    if (!settings_.shadows) {
      return true;
    }
    ++raysTraced;
    const glm::vec3 toLight = lightPoint - point.shadowRayOrigin;
    const float distance = glm::length(toLight);
    // Stop just short of the light point, or the light's own quad would occlude it.
    return !rays_.occluded(point.shadowRayOrigin, toLight / distance, (1.0f - 1e-4f) * distance);
  }

  // How a light point lies from a surface point: both cosines are 0 when either faces away.
  struct Geometry {
    glm::vec3 toLight{0.0f};
    float squaredDistance = 0.0f;
    float cosineAtPoint = 0.0f;
    float cosineAtLight = 0.0f;
  };

  static Geometry lightGeometry(const SurfacePoint& point, glm::vec3 lightPoint,
                                glm::vec3 lightNormal) {
    Geometry geometry;
    const glm::vec3 offset = lightPoint - point.position;
    geometry.squaredDistance = glm::dot(offset, offset);
    if (geometry.squaredDistance <= 0.0f) {
      return geometry;
    }
    geometry.toLight = offset / std::sqrt(geometry.squaredDistance);
    geometry.cosineAtPoint = std::max(0.0f, glm::dot(point.normal, geometry.toLight));
    geometry.cosineAtLight = std::max(0.0f, glm::dot(lightNormal, -geometry.toLight));
    return geometry;
  }

  glm::vec3 stratifiedLight(const SurfacePoint& point, const LightSource& source,
                            std::uint64_t pixelIndex, std::size_t lightIndex,
                            std::uint64_t& raysTraced) const {
    const int side = strataPerSide_;
    const float cellWeight = 1.0f / static_cast<float>(side * side);
    glm::vec3 sum(0.0f);
    for (int row = 0; row < side; ++row) {
      for (int column = 0; column < side; ++column) {
        const int sample = row * side + column;
        const glm::vec2 jitter = sampleJitter(settings_.seed, pixelIndex, lightIndex,
                                              static_cast<std::uint64_t>(sample));
        const glm::vec2 u = (glm::vec2(column, row) + jitter) / static_cast<float>(side);
        const LightPoint light = lightPoint(source, u, point.position);
        const Geometry geometry = lightGeometry(point, light.position, light.normal);
        if (geometry.cosineAtPoint <= 0.0f || geometry.cosineAtLight <= 0.0f) {
          continue;
        }
        const float transfer = geometry.cosineAtPoint * geometry.cosineAtLight /
                               geometry.squaredDistance * light.jacobian * cellWeight;
        const glm::vec3 contribution =
            reflectance(point, geometry.toLight) * light.emission * transfer;
        if (contribution != glm::vec3(0.0f) && visible(point, light.position, raysTraced)) {
          sum += contribution;
        }
      }
    }
    return sum;
  }

  // One diffuse bounce: with cosine-distributed directions the estimate of
  // (albedo/pi) * integral of L cos over the hemisphere is albedo times the mean of L.
  glm::vec3 oneBounce(const SurfacePoint& point, std::uint64_t pixelIndex,
                      std::uint64_t& raysTraced) const {
    // Sample streams of their own, apart from the direct light's (light indices 0, 1, ...).
    constexpr std::uint64_t kDirectionStream = 1ull << 32;
    constexpr std::uint64_t kLightPointStream = 2ull << 32;
    const int side = strataPerSide(settings_.samplesPerPixel);
    const glm::vec3 normal = point.normal;
    const glm::vec3 other =
        std::abs(normal.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 tangent = glm::normalize(glm::cross(normal, other));
    const glm::vec3 bitangent = glm::cross(normal, tangent);
    glm::vec3 sum(0.0f);
    for (int row = 0; row < side; ++row) {
      for (int column = 0; column < side; ++column) {
        const auto sample = static_cast<std::uint64_t>(row * side + column);
        const glm::vec2 jitter = sampleJitter(settings_.seed, pixelIndex, kDirectionStream, sample);
        const glm::vec2 u = (glm::vec2(column, row) + jitter) / static_cast<float>(side);
        const float radius = std::sqrt(u.x);
        const float angle = 2.0f * kPi * u.y;
        const glm::vec3 direction = glm::normalize(radius * std::cos(angle) * tangent +
                                                   radius * std::sin(angle) * bitangent +
                                                   std::sqrt(std::max(0.0f, 1.0f - u.x)) * normal);
        // A smooth normal leans off the face, so some of its hemisphere lies behind the face:
        // light cannot arrive through the opaque surface from there (a ray would hit the
        // surface itself and see it lit from the front, a light leak).
        if (glm::dot(direction, point.faceNormal) <= 0.0f) {
          continue;
        }
        ++raysTraced;
        const RayHit hit = rays_.intersect(point.shadowRayOrigin, direction, 0.0f,
                                           std::numeric_limits<float>::infinity());
        // Lights are emitters only: the direct light already counts what they emit.
        if (hit.kind != RayHit::Kind::Surface || materialOf(hit).emits) {
          continue;
        }
        const SurfacePoint bounce = surfacePoint(hit, direction);
        for (std::size_t light = 0; light < lights_.size(); ++light) {
          sum += bounceLight(
              bounce, lights_[light],
              sampleJitter(settings_.seed, pixelIndex, kLightPointStream + light, sample),
              raysTraced);
        }
      }
    }
    return point.albedo * sum / static_cast<float>(side * side);
  }

  // The diffuse radiance a surface reflects from one uniformly placed sample of a light.
  glm::vec3 bounceLight(const SurfacePoint& point, const LightSource& source, glm::vec2 uv,
                        std::uint64_t& raysTraced) const {
    const LightPoint light = lightPoint(source, uv, point.position);
    const Geometry geometry = lightGeometry(point, light.position, light.normal);
    if (geometry.cosineAtPoint <= 0.0f || geometry.cosineAtLight <= 0.0f) {
      return glm::vec3(0.0f);
    }
    const float transfer =
        geometry.cosineAtPoint * geometry.cosineAtLight / geometry.squaredDistance * light.jacobian;
    const glm::vec3 contribution = point.albedo / kPi * light.emission * transfer;
    if (contribution == glm::vec3(0.0f) || !visible(point, light.position, raysTraced)) {
      return glm::vec3(0.0f);
    }
    return contribution;
  }

  glm::vec3 vplLight(const SurfacePoint& point, const LightSource& source,
                     std::uint64_t& raysTraced) const {
    glm::vec3 sum(0.0f);
    for (const Vpl& vpl : source.vpls) {
      const Geometry geometry = lightGeometry(point, vpl.position, vpl.normal);
      if (geometry.cosineAtPoint <= 0.0f || geometry.cosineAtLight <= 0.0f) {
        continue;
      }
      // The bounded form factor: 1/r^2 flattens out to a disc of the VPL's area near the light.
      const float transfer = kPi * vpl.area * geometry.cosineAtPoint * geometry.cosineAtLight /
                             (kPi * geometry.squaredDistance + vpl.area);
      const glm::vec3 contribution = reflectance(point, geometry.toLight) * vpl.radiance * transfer;
      if (contribution != glm::vec3(0.0f) && visible(point, vpl.position, raysTraced)) {
        sum += contribution;
      }
    }
    return sum;
  }

  const Scene& scene_;
  const ReferenceSettings& settings_;
  const FrameGeometry& geometry_;
  const RayScene& rays_;
  const Camera& camera_;
  std::vector<const Image*> textureFrames_;  // per Scene::textures entry
  std::vector<LightSource> lights_;
  int strataPerSide_ = 1;
  float shadowRayOffset_ = 0.0f;
};

}  // namespace

Image renderReference(const Scene& scene, const ReferenceSettings& settings,
                      ReferenceStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  Camera camera = scene.camera;
  camera.size = outputSize(scene, settings);
  const FrameGeometry geometry = buildFrameGeometry(scene, settings.frame);
  const RayScene rays(geometry, scene.lights);
  const PixelRenderer renderer(scene, settings, geometry, rays, camera);

  const auto cancelled = [&settings] {
    return settings.cancel != nullptr && settings.cancel->load(std::memory_order_relaxed);
  };
  const int width = camera.size.x;
  const int height = camera.size.y;
  Image image(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  std::atomic<std::uint64_t> raysTraced{0};
  // Bands of rows rendered one after the other, each in parallel tiles, so that progress is
  // reported from this thread between bands (about 64 reports per image).
  const int rowsPerBand = std::max(1, height / 64);
  for (int firstRow = 0; firstRow < height; firstRow += rowsPerBand) {
    if (cancelled()) {
      throw Cancelled();
    }
    const int endRow = std::min(height, firstRow + rowsPerBand);
    const tbb::blocked_range2d<int> band(firstRow, endRow, kTileSize, 0, width, kTileSize);
    tbb::parallel_for(band, [&](const tbb::blocked_range2d<int>& tile) {
      std::uint64_t tileRays = 0;
      for (int y = tile.rows().begin(); y != tile.rows().end() && !cancelled(); ++y) {
        for (int x = tile.cols().begin(); x != tile.cols().end(); ++x) {
          image.at(x, y) = glm::vec4(renderer.pixel(x, y, tileRays), 1.0f);
        }
      }
      raysTraced.fetch_add(tileRays, std::memory_order_relaxed);
    });
    if (cancelled()) {
      throw Cancelled();
    }
    if (settings.progress) {
      settings.progress(static_cast<double>(endRow) / height);
    }
  }
  if (stats != nullptr) {
    stats->raysTraced = raysTraced.load();
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return image;
}

}  // namespace penumbra
