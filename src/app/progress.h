#pragma once
// Progress of a long render on stderr: a bar with the elapsed time and an ETA on a terminal,
// plain progress lines (at most one per 10% step) when stderr is not a terminal.

#include <chrono>
#include <string>

namespace penumbra::app {

class ProgressReport {
 public:
  explicit ProgressReport(std::string label);
  // fraction in [0, 1]; cheap to call often.
  void update(double fraction);
  // Ends the bar's line (or prints the last plain line).
  void finish();

 private:
  std::string label_;
  bool terminal_ = false;
  int lastPercentShown_ = -1;
  double lastFraction_ = 0.0;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace penumbra::app
