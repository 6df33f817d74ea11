#pragma once
// The CPU reference on Embree 3: the same quantity as the GPU modes, for the same camera, pixel
// centres, materials, textures and normals, with exact shadow rays.

#include <atomic>
#include <cstdint>
#include <functional>

#include "image/image.h"
#include "scene/scene.h"

namespace penumbra {

struct ReferenceSettings {
  enum class Sampling {
    Stratified,  // `reference`: stratified samples over each light, texture read bilinearly
    Vpl,         // `reference-vpl`: the GPU modes' VPLs, with exact visibility
  };
  Sampling sampling = Sampling::Stratified;
  int samplesPerPixel =
      256;                 // light samples per pixel and light (Stratified); rounded up to a square
  int vplsPerLight = 256;  // Vpl
  std::uint64_t seed = 1;
  bool shadows = true;  // false: V = 1, as the GPU modes' --no-shadows
  // 1: add one diffuse bounce, path traced: samplesPerPixel cosine-distributed rays from each
  // visible point (stratified), and at each surface they hit the direct light of every light
  // from one light sample with its shadow ray, times that surface's albedo/pi. The bounce is
  // diffuse at both ends, like the GPU modes' indirect light (docs/indirect.md).
  int bounces = 0;
  int frame = 0;
  glm::ivec2 size{0};  // 0: the camera's screen size
  // Called now and then with the fraction done (0..1), from the calling thread.
  std::function<void(double)> progress;
  // Set from elsewhere (a signal handler) to stop early; renderReference then throws Cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

struct ReferenceStats {
  std::uint64_t raysTraced = 0;
  double seconds = 0.0;
};

Image renderReference(const Scene& scene, const ReferenceSettings& settings,
                      ReferenceStats* stats = nullptr);

}  // namespace penumbra
