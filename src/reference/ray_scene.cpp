#include "reference/ray_scene.h"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace penumbra {
namespace {

std::string embreeErrorText(RTCError error) {
  switch (error) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    case RTC_ERROR_UNKNOWN:
      break;
  }
  return "unknown error";
}

void throwIfFailed(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree: ") + what + ": " + embreeErrorText(error));
  }
}

// Copies into buffers Embree allocates itself: it reads vertices with 16-byte loads and so wants
// padding after the last one, which a std::vector<glm::vec3> does not have.
unsigned attachTriangles(RTCDevice device, RTCScene scene, const std::vector<glm::vec3>& positions,
                         const std::vector<glm::uvec3>& triangles) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertexBuffer = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3), positions.size()));
  auto* indexBuffer = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3), triangles.size()));
  throwIfFailed(device, "allocating geometry buffers");
  std::memcpy(vertexBuffer, positions.data(), positions.size() * sizeof(glm::vec3));
  std::memcpy(indexBuffer, triangles.data(), triangles.size() * sizeof(glm::uvec3));
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  throwIfFailed(device, "building geometry");
  return id;
}

}  // namespace

RayScene::RayScene(const FrameGeometry& geometry, const std::vector<Light>& lights) {
  device_ = rtcNewDevice(nullptr);
  if (device_ == nullptr) {
    throw std::runtime_error("Embree: cannot create a device: " +
                             embreeErrorText(rtcGetDeviceError(nullptr)));
  }
  try {
    scene_ = rtcNewScene(device_);
    // Robust traversal: a ray through the shared diagonal of a light quad, or an edge shared by two
    // scene triangles, must not slip between them.
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    if (!geometry.triangles.empty()) {
      surfaceGeometry_ = attachTriangles(device_, scene_, geometry.positions, geometry.triangles);
    }
    if (!lights.empty()) {
      std::vector<glm::vec3> corners;
      std::vector<glm::uvec3> triangles;
      for (const Light& light : lights) {
        const auto first = static_cast<unsigned>(corners.size());
        corners.insert(corners.end(), light.quad.corners.begin(), light.quad.corners.end());
        triangles.emplace_back(first, first + 1, first + 2);
        triangles.emplace_back(first, first + 2, first + 3);
      }
      lightGeometry_ = attachTriangles(device_, scene_, corners, triangles);
    }
    rtcCommitScene(scene_);
    throwIfFailed(device_, "building the scene");
  } catch (...) {
    if (scene_ != nullptr) {
      rtcReleaseScene(scene_);
    }
    rtcReleaseDevice(device_);
    throw;
  }
}

RayScene::~RayScene() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

RayHit RayScene::intersect(glm::vec3 origin, glm::vec3 direction, float tNear, float tFar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  query.ray.org_x = origin.x;
  query.ray.org_y = origin.y;
  query.ray.org_z = origin.z;
  query.ray.dir_x = direction.x;
  query.ray.dir_y = direction.y;
  query.ray.dir_z = direction.z;
  query.ray.tnear = tNear;
  query.ray.tfar = tFar;
  query.ray.mask = std::numeric_limits<unsigned>::max();
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &query);

  RayHit hit;
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    return hit;
  }
  hit.distance = query.ray.tfar;
  hit.barycentric = {query.hit.u, query.hit.v};
  if (query.hit.geomID == lightGeometry_) {
    hit.kind = RayHit::Kind::Light;
    hit.index = static_cast<int>(query.hit.primID / 2);
    hit.lightTriangle = static_cast<int>(query.hit.primID % 2);
  } else {
    hit.kind = RayHit::Kind::Surface;
    hit.index = static_cast<int>(query.hit.primID);
  }
  return hit;
}

bool RayScene::occluded(glm::vec3 origin, glm::vec3 direction, float tFar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay query{};
  query.org_x = origin.x;
  query.org_y = origin.y;
  query.org_z = origin.z;
  query.dir_x = direction.x;
  query.dir_y = direction.y;
  query.dir_z = direction.z;
  query.tnear = 0.0f;
  query.tfar = tFar;
  query.mask = std::numeric_limits<unsigned>::max();
  rtcOccluded1(scene_, &context, &query);
  // Embree marks an occluded ray by setting tfar to -inf.
  return query.tfar < 0.0f;
}

RayHit traceCameraRay(const RayScene& rays, const Camera& camera, glm::vec3 direction) {
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  const float cosineToAxis = glm::dot(direction, forward);
  return rays.intersect(camera.position, direction, camera.nearPlane / cosineToAxis,
                        camera.farPlane / cosineToAxis);
}

}  // namespace penumbra
