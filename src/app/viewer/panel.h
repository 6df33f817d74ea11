#pragma once
// The viewer's ImGui widgets: the renderer's settings, the legend of the shown view, the pass
// timings with a frame-time graph, and the help.

#include <deque>
#include <vector>

#include "render/debug_view_registry.h"
#include "render/frame.h"
#include "render/timing.h"

namespace penumbra::app {

// One widget per settings field; returns whether any changed. `imageSize` tells how many
// pyramid levels the coarsest size gives.
bool drawSettingsPanel(RenderSettings& settings, glm::ivec2 imageSize);

// The colour map with its range and quantity, or the palette with what each colour means, or
// the exposure of a radiance view. Returns true when the user asks to refit the range.
bool drawLegend(DebugViewSource& view, float exposure);

// Frame times of the last frames, oldest first, in milliseconds.
class FrameTimeHistory {
 public:
  void add(double milliseconds);
  const std::deque<float>& values() const { return values_; }
  float mean() const;

 private:
  std::deque<float> values_;
};

void drawTimings(const std::vector<StageTime>& passes, TimingMethod method,
                 const FrameTimeHistory& frameTimes);

// The controls: what each key and mouse action does.
void drawHelp();

}  // namespace penumbra::app
