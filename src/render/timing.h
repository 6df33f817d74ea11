#pragma once
// Time per pass. On llvmpipe GL timer queries return 0, so there the CPU clock is read after
// glFinish() at both ends of each pass; elsewhere GL_TIME_ELAPSED queries measure the GPU.

#include <string>
#include <vector>

#include "gl/handles.h"

namespace penumbra {

enum class TimingMethod { CpuAfterFinish, GpuTimerQueries };

const char* timingMethodName(TimingMethod method);  // "cpu-after-glfinish", "gl-timer-queries"

struct PassTime {
  std::string pass;
  double milliseconds = 0.0;
};

class PassTimer {
 public:
  explicit PassTimer(TimingMethod method) : method_(method) {}
  TimingMethod method() const { return method_; }

  // Starts a frame's measurements; begin/end bracket each pass, without nesting.
  void startFrame();
  void begin(const std::string& pass);
  void end();
  // The frame's passes in the order they ran (waits for the GPU's answers).
  std::vector<PassTime> finishFrame();

 private:
  TimingMethod method_;
  std::vector<std::string> passes_;
  std::vector<double> cpuMilliseconds_;
  std::vector<gl::Query> queries_;
  double passStart_ = 0.0;
};

}  // namespace penumbra
