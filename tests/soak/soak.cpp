// The soak test: one process renders many frames of an animated scene with a video light at a
// small size, and checks that nothing accumulates. Usage: penumbra_soak SCENE [FRAMES]
//
// Every kSampleInterval frames it samples the resident memory (/proc/self/statm) and the live GL
// objects (gl::liveObjectCount). After the warm-up, the live count must not change at all, and
// the resident memory must not grow by more than kAllowedGrowthBytes. It also fails on any GL
// error. Prints every sample, so the figures in docs/robustness.md come from its output.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "gl/context.h"
#include "gl/debug.h"
#include "gl/handles.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace penumbra {
namespace {

// The frame's cost on llvmpipe is mostly shadow rays (pixels x VPLs) and voxelization (the grid's
// resolution); these keep 3000 frames within minutes while every pass still runs each frame.
constexpr glm::ivec2 kImageSize{64, 64};
constexpr int kVplsPerLight = 16;
constexpr int kVoxelResolution = 32;
constexpr int kDefaultFrames = 3000;
constexpr int kSampleInterval = 100;
// Every kNaiveEvery-th frame is rendered in naive mode, so that switching modes back and forth is
// part of the run (10% of the frames).
constexpr int kNaiveEvery = 10;
// Caches that fill once (shader compilation in the driver, the video decoder's frame queue,
// allocator arenas) settle within the first frames; growth is measured from here on.
constexpr int kWarmUpFrames = 300;
// A leak of one 64x64 RGBA float image per frame (64 KiB) would add about 170 MiB over the 2700
// frames after the warm-up, and a leak of 8 KiB per frame about 21 MiB. The allocator and the
// driver move the resident size by a few MiB without leaking (measured: docs/robustness.md), so
// 16 MiB separates the two.
constexpr std::int64_t kAllowedGrowthBytes = 16 << 20;

std::int64_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::int64_t totalPages = 0;
  std::int64_t residentPages = 0;
  statm >> totalPages >> residentPages;
  return residentPages * static_cast<std::int64_t>(sysconf(_SC_PAGESIZE));
}

double mebibytes(std::int64_t bytes) {
  return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

struct Sample {
  int frame = 0;
  std::int64_t resident = 0;
  std::int64_t liveObjects = 0;
};

bool allFinite(const Image& image) {
  for (const glm::vec4& pixel : image.pixels)
    if (!std::isfinite(pixel.r) || !std::isfinite(pixel.g) || !std::isfinite(pixel.b))
      return false;
  return true;
}

int run(const std::filesystem::path& sceneFile, int frames) {
  gl::HeadlessContext context;
  std::printf(
      "soak: %s, %d frames at %dx%d, %d VPLs per light, shadows on a %d^3 voxel grid, every %dth "
      "frame naive, on %s\n",
      sceneFile.string().c_str(), frames, kImageSize.x, kImageSize.y, kVplsPerLight,
      kVoxelResolution, kNaiveEvery, context.info().renderer.c_str());
  Scene scene = loadScene(parseSceneFile(sceneFile));
  bool animatedLight = false;
  for (const Light& light : scene.lights)
    animatedLight =
        animatedLight || (light.texture >= 0 && scene.textures[light.texture]->animated());
  std::printf("soak: the scene %s a video light\n", animatedLight ? "has" : "has NO");

  Renderer renderer(scene, kImageSize);
  RenderSettings hierarchical;
  hierarchical.vplsPerLight = kVplsPerLight;
  hierarchical.shadows.voxels.resolution = kVoxelResolution;
  RenderSettings naive = hierarchical;
  naive.mode = RenderMode::Naive;

  std::vector<Sample> samples{{-1, residentBytes(), gl::liveObjectCount()}};
  std::printf("soak: before the first frame: resident %.1f MiB, %lld live GL objects\n",
              mebibytes(samples.back().resident),
              static_cast<long long>(samples.back().liveObjects));
  bool finite = true;
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < frames; ++frame) {
    renderer.render(frame, frame % kNaiveEvery == kNaiveEvery - 1 ? naive : hierarchical);
    const Image image = renderer.readRadiance();
    finite = finite && allFinite(image);
    if ((frame + 1) % kSampleInterval == 0) {
      samples.push_back({frame + 1, residentBytes(), gl::liveObjectCount()});
      std::printf("soak: frame %5d: resident %7.1f MiB, %lld live GL objects\n", frame + 1,
                  mebibytes(samples.back().resident),
                  static_cast<long long>(samples.back().liveObjects));
      std::fflush(stdout);
    }
  }
  gl::drainErrors();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("soak: %d frames in %.1f s (%.1f ms a frame)\n", frames, seconds,
              1000.0 * seconds / frames);

  const Sample* warm = nullptr;
  std::int64_t peak = 0;
  bool liveCountConstant = true;
  for (const Sample& sample : samples) {
    if (sample.frame < kWarmUpFrames)
      continue;
    if (warm == nullptr)
      warm = &sample;
    peak = std::max(peak, sample.resident);
    liveCountConstant = liveCountConstant && sample.liveObjects == warm->liveObjects;
  }
  if (warm == nullptr) {
    std::printf("soak: FAIL: %d frames do not pass the warm-up of %d\n", frames, kWarmUpFrames);
    return 1;
  }
  const std::int64_t growth = peak - warm->resident;
  std::printf(
      "soak: after the warm-up (frame %d): resident %.1f MiB at the start, %.1f MiB at the end, "
      "%.1f MiB peak; growth %.2f MiB (allowed %.0f MiB)\n",
      warm->frame, mebibytes(warm->resident), mebibytes(samples.back().resident), mebibytes(peak),
      mebibytes(growth), mebibytes(kAllowedGrowthBytes));
  std::printf("soak: live GL objects %lld after the warm-up, %lld at the end\n",
              static_cast<long long>(warm->liveObjects),
              static_cast<long long>(samples.back().liveObjects));

  bool passed = true;
  const auto check = [&passed](bool condition, const char* failure) {
    if (!condition) {
      std::printf("soak: FAIL: %s\n", failure);
      passed = false;
    }
  };
  check(liveCountConstant, "the number of live GL objects changed after the warm-up");
  check(growth <= kAllowedGrowthBytes, "the resident memory grew beyond the allowed bound");
  check(gl::errorCount() == 0, "GL errors were reported (see above)");
  check(finite, "a frame had non-finite pixels");
  std::printf("soak: %s\n", passed ? "pass" : "FAIL");
  return passed ? 0 : 1;
}

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: penumbra_soak SCENE [FRAMES]\n");
    return 2;
  }
  try {
    const int frames = argc == 3 ? std::stoi(argv[2]) : penumbra::kDefaultFrames;
    return penumbra::run(argv[1], frames);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "soak: error: %s\n", error.what());
    return 1;
  }
}
