#include "app/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace penumbra::app {
namespace {

constexpr int kBarWidth = 30;
// A terminal is redrawn at most this often: faster redraws only cost time and flicker.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);

std::string durationText(double seconds) {
  const long total = std::lround(seconds);
  char text[32];
  if (total < 60) {
    std::snprintf(text, sizeof text, "%lds", total);
  } else if (total < 3600) {
    std::snprintf(text, sizeof text, "%ldm%02lds", total / 60, total % 60);
  } else {
    std::snprintf(text, sizeof text, "%ldh%02ldm", total / 3600, total % 3600 / 60);
  }
  return text;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ProgressReport::ProgressReport(std::string label, ProgressStyle style)
    : label_(std::move(label)),
      terminal_(isatty(STDERR_FILENO) != 0),
      shown_(style == ProgressStyle::BarOrLines || (style == ProgressStyle::BarOnly && terminal_)),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

void ProgressReport::update(double fraction, const std::string& detail) {
  if (!shown_)
    return;
  detail_ = detail;
  // Written as !(x >= 0) so that a NaN counts as no progress.
  fraction = !(fraction >= 0.0) ? 0.0 : std::min(fraction, 1.0);
  lastFraction_ = fraction;
  const int percent = static_cast<int>(fraction * 100.0);
  const double elapsed = secondsSince(start_);
  if (terminal_) {
    const auto now = std::chrono::steady_clock::now();
    if (lastPercentShown_ >= 0 && now - lastDraw_ < kRedrawInterval) {
      return;
    }
    const int filled = static_cast<int>(fraction * kBarWidth);
    const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                            std::string(static_cast<std::size_t>(kBarWidth - filled), '.');
    const std::string eta =
        fraction > 0.0 ? durationText(elapsed * (1.0 - fraction) / fraction) : std::string("?");
    // \r returns to the line's start and \033[K clears what a longer earlier line left behind.
    const std::string detailText = detail_.empty() ? std::string() : "  " + detail_;
    std::fprintf(stderr, "\r%s [%s] %3d%%%s  elapsed %s  ETA %s\033[K", label_.c_str(), bar.c_str(),
                 percent, detailText.c_str(), durationText(elapsed).c_str(), eta.c_str());
    std::fflush(stderr);
    lastDraw_ = now;
    lastPercentShown_ = percent;
    return;
  }
  const int step = percent / 10 * 10;
  if (step > lastPercentShown_) {
    std::fprintf(stderr, "%s: %d%%  elapsed %s\n", label_.c_str(), step,
                 durationText(elapsed).c_str());
    lastPercentShown_ = step;
  }
}

void ProgressReport::finish() {
  if (finished_ || !shown_) {
    return;
  }
  finished_ = true;
  const int percent = static_cast<int>(lastFraction_ * 100.0);
  if (terminal_) {
    // Draw the final state whatever the redraw interval says, then end the line.
    lastPercentShown_ = -1;
    update(lastFraction_, detail_);
    std::fputc('\n', stderr);
  } else if (percent > lastPercentShown_) {
    std::fprintf(stderr, "%s: %d%%  elapsed %s\n", label_.c_str(), percent,
                 durationText(secondsSince(start_)).c_str());
  }
  std::fflush(stderr);
}

}  // namespace penumbra::app
