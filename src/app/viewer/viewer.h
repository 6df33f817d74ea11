#pragma once
// `penumbra view`: the renderer in a window, with every setting live, any intermediate texture
// as the picture, pass timings, and keys to move the camera, pause, save and reload shaders.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/frame.h"
#include "scene/scene.h"

namespace penumbra::app {

// The panel's width in pixels: the window is this much wider than the picture, and the panel
// stands on the picture's right, so that it never covers it.
constexpr int kPanelWidth = 400;

struct ViewerOptions {
  glm::ivec2 imageSize{512, 512};  // the picture's; the window adds the panel beside it
  RenderSettings settings;
  std::string view = "radiance";  // a name of displayViewInfos()
  int level = 0;
  float exposure = 0.0f;
  bool showHelp = true;
  // Automation: after `frames` frames (0: never), save `screenshot` (when set) and, with
  // `exitAfterFrames`, close.
  int frames = 0;
  std::optional<std::filesystem::path> screenshot;
  bool exitAfterFrames = false;
  // Automation: every frame after the first turns the camera by 1/orbitFrames of a turn about
  // its target (0: it stays), so that the frame time can be measured with the camera moving.
  int orbitFrames = 0;
};

struct ViewerSummary {
  int frames = 0;               // frames shown
  glm::ivec2 imageSize{0};      // of the last frame's picture (the window less the panel)
  double medianFrameMs = 0.0;   // wall clock between frames, the first frame left out
  double medianRenderMs = 0.0;  // sum of the pass times, the first frame left out
  std::string renderError;      // why the last frame could not be rendered; empty when it was
  std::size_t glErrors = 0;     // GL_DEBUG_TYPE_ERROR messages and glGetError() failures
  std::vector<StageTime> medianStages;  // each stage's median, in the order of the last frame
};

// Runs until the window is closed (or the automation ends). Throws gl::ContextError without a
// display or GL 4.5 core, gl::ShaderError when the first shaders fail, ImageError when the
// automation's screenshot cannot be written.
ViewerSummary runViewer(Scene& scene, const ViewerOptions& options);

}  // namespace penumbra::app
