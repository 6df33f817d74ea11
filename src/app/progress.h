#pragma once
// Progress of a long render on stderr: a bar with the elapsed time and an ETA on a terminal,
// and when stderr is not a terminal plain progress lines (at most one per 10% step) or nothing.

#include <chrono>
#include <string>

namespace penumbra::app {

enum class ProgressStyle {
  BarOrLines,  // the bar on a terminal, plain lines elsewhere
  BarOnly,     // the bar on a terminal, nothing elsewhere
  Silent,      // nothing (--quiet)
};

class ProgressReport {
 public:
  explicit ProgressReport(std::string label, ProgressStyle style = ProgressStyle::BarOrLines);
  // fraction in [0, 1]; cheap to call often. `detail` (e.g. "frame 3/10") follows the bar.
  void update(double fraction, const std::string& detail = {});
  // Ends the bar's line (or prints the last plain line).
  void finish();

 private:
  std::string label_;
  std::string detail_;
  bool terminal_ = false;
  bool shown_ = false;
  int lastPercentShown_ = -1;
  double lastFraction_ = 0.0;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace penumbra::app
