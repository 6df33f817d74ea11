#include "render/timing.h"

#include <chrono>

namespace penumbra {
namespace {

double nowMilliseconds() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

const char* timingMethodName(TimingMethod method) {
  return method == TimingMethod::CpuAfterFinish ? "cpu-after-glfinish" : "gl-timer-queries";
}

void PassTimer::startFrame() {
  passes_.clear();
  cpuMilliseconds_.clear();
}

void PassTimer::begin(const std::string& pass) {
  const std::size_t index = passes_.size();
  passes_.push_back(pass);
  if (method_ == TimingMethod::CpuAfterFinish) {
    glFinish();
    passStart_ = nowMilliseconds();
    return;
  }
  // Queries are kept from frame to frame: a pass reuses the query of its slot.
  if (queries_.size() <= index)
    queries_.emplace_back(GL_TIME_ELAPSED);
  glBeginQuery(GL_TIME_ELAPSED, queries_[index].id());
}

void PassTimer::end() {
  if (method_ == TimingMethod::CpuAfterFinish) {
    glFinish();
    cpuMilliseconds_.push_back(nowMilliseconds() - passStart_);
    return;
  }
  glEndQuery(GL_TIME_ELAPSED);
}

std::vector<PassTime> PassTimer::finishFrame() {
  std::vector<PassTime> times;
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    double milliseconds = 0.0;
    if (method_ == TimingMethod::CpuAfterFinish) {
      milliseconds = cpuMilliseconds_[i];
    } else {
      GLuint64 nanoseconds = 0;
      glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &nanoseconds);
      milliseconds = static_cast<double>(nanoseconds) * 1e-6;
    }
    times.push_back({passes_[i], milliseconds});
  }
  return times;
}

}  // namespace penumbra
