#include "render/timing.h"

#include <chrono>

namespace penumbra {
namespace {

double nowMilliseconds() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

const char* stageName(Stage stage) {
  switch (stage) {
    case Stage::Upload:
      return "upload";
    case Stage::Vpls:
      return "vpls";
    case Stage::GBuffer:
      return "gbuffer";
    case Stage::Voxelize:
      return "voxelize";
    case Stage::Bvh:
      return "bvh";
    case Stage::Discontinuity:
      return "discontinuity";
    case Stage::Visibility:
      return "visibility";
    case Stage::Refinement:
      return "refinement";
    case Stage::Gather:
      return "gather";
    case Stage::Upsample:
      return "upsample";
    case Stage::BounceRsm:
      return "bounce rsm";
    case Stage::BounceVpls:
      return "bounce vpls";
    case Stage::BounceShadows:
      return "bounce shadows";
    case Stage::BounceGather:
      return "bounce gather";
  }
  return "unknown";
}

}  // namespace

const char* timingMethodName(TimingMethod method) {
  return method == TimingMethod::CpuAfterFinish ? "cpu-after-glfinish" : "gl-timer-queries";
}

std::string stageLabel(StageKey key) {
  std::string label = stageName(key.stage);
  if (key.level != StageKey::kNoLevel)
    label += "/" + std::to_string(key.level);
  return label;
}

bool isSharedStage(Stage stage) {
  return stage == Stage::Upload || stage == Stage::Vpls || stage == Stage::GBuffer ||
         stage == Stage::Voxelize || stage == Stage::Bvh;
}

void StageTimer::startFrame() {
  stages_.clear();
  cpuMilliseconds_.clear();
}

StageTimer::Scope StageTimer::time(Stage stage, int level) {
  const std::size_t index = stages_.size();
  stages_.push_back({stage, level});
  if (method_ == TimingMethod::CpuAfterFinish) {
    glFinish();
    stageStart_ = nowMilliseconds();
    return Scope(*this);
  }
  // Queries are kept from frame to frame: a stage reuses the query of its slot.
  if (queries_.size() <= index)
    queries_.emplace_back(GL_TIME_ELAPSED);
  glBeginQuery(GL_TIME_ELAPSED, queries_[index].id());
  return Scope(*this);
}

void StageTimer::end() {
  if (method_ == TimingMethod::CpuAfterFinish) {
    glFinish();
    cpuMilliseconds_.push_back(nowMilliseconds() - stageStart_);
    return;
  }
  glEndQuery(GL_TIME_ELAPSED);
}

std::vector<StageTime> StageTimer::finishFrame() {
  std::vector<StageTime> times;
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    double milliseconds = 0.0;
    if (method_ == TimingMethod::CpuAfterFinish) {
      milliseconds = cpuMilliseconds_[i];
    } else {
      GLuint64 nanoseconds = 0;
      glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &nanoseconds);
      milliseconds = static_cast<double>(nanoseconds) * 1e-6;
    }
    times.push_back({stages_[i], milliseconds});
  }
  return times;
}

}  // namespace penumbra
