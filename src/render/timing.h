#pragma once
// Time per stage of a frame, keyed by stage and level. How a stage is measured is the caller's
// choice, given as a value: on llvmpipe GL timer queries return 0, so there the CPU clock is read
// after glFinish() at both ends of each stage; elsewhere GL_TIME_ELAPSED queries measure the GPU.

#include <compare>
#include <string>
#include <vector>

#include "gl/handles.h"

namespace penumbra {

enum class TimingMethod { CpuAfterFinish, GpuTimerQueries };

const char* timingMethodName(TimingMethod method);  // "cpu-after-glfinish", "gl-timer-queries"

enum class Stage {
  Upload,         // the scene to the GPU
  Vpls,           // light sampling
  GBuffer,        //
  Voxelize,       // the voxel grid of the shadows
  Bvh,            // exact shadows: the top level over the objects' hierarchies
  Discontinuity,  // hierarchical: the reduced G-buffer and its discontinuities
  Visibility,     // hierarchical, per level: the visibility masks
  Refinement,     // hierarchical, per level: the texel states and work lists
  Gather,         // naive: every pixel; hierarchical: per level
  Upsample,       // hierarchical: upsample and combine
  BounceRsm,      // indirect light: the reflective shadow maps
  BounceVpls,     // indirect light: the secondary VPLs
  BounceShadows,  // indirect light: their visibility from the light
  BounceGather,   // indirect light: their gather
};

// A stage at one level, or at none (kNoLevel) for stages that run once a frame.
struct StageKey {
  static constexpr int kNoLevel = -1;
  Stage stage = Stage::Upload;
  int level = kNoLevel;
  auto operator<=>(const StageKey&) const = default;
};

// The stage's name as reports print it: "upload", "bounce rsm", "gather" (naive), "gather/2".
std::string stageLabel(StageKey key);
// The stages every mode runs, which `bench` subtracts from the frame to give the lighting time.
bool isSharedStage(Stage stage);

struct StageTime {
  StageKey key;
  double milliseconds = 0.0;
};

class StageTimer {
 public:
  explicit StageTimer(TimingMethod method) : method_(method) {}
  TimingMethod method() const { return method_; }

  // Measures from its construction to its end of scope; scopes do not nest.
  class [[nodiscard]] Scope {
   public:
    ~Scope() { timer_.end(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    friend class StageTimer;
    explicit Scope(StageTimer& timer) : timer_(timer) {}
    StageTimer& timer_;
  };

  // Starts a frame's measurements.
  void startFrame();
  Scope time(Stage stage, int level = StageKey::kNoLevel);
  // The frame's stages in the order they ran (waits for the GPU's answers).
  std::vector<StageTime> finishFrame();

 private:
  void end();

  TimingMethod method_;
  std::vector<StageKey> stages_;
  std::vector<double> cpuMilliseconds_;
  std::vector<gl::Query> queries_;
  double stageStart_ = 0.0;
};

}  // namespace penumbra
