#include "app/viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <glm/gtc/constants.hpp>

#include "app/viewer/camera_controller.h"
#include "app/viewer/display_pass.h"
#include "app/viewer/panel.h"
#include "app/viewer/window.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/debug_view_registry.h"
#include "render/device_profile.h"
#include "render/levels.h"

namespace penumbra::app {
namespace {

using Clock = std::chrono::steady_clock;

// While nothing changes (animation paused, no input), the loop sleeps this long between checks.
constexpr double kIdleWaitSeconds = 0.1;
// The animation's time step per frame (spec: frame f shows time f / 30 s).
constexpr double kFramesPerSecond = 30.0;

double millisecondsBetween(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

double median(std::vector<double> values) {
  if (values.empty())
    return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double totalMilliseconds(const std::vector<StageTime>& passes) {
  double total = 0.0;
  for (const StageTime& pass : passes)
    total += pass.milliseconds;
  return total;
}

// The window's back buffer as shown (after the interface is drawn), decoded to linear values
// so that saveImage's sRGB encoding gives back the same 8-bit pixels.
Image readWindow(glm::ivec2 size) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size.x) * size.y * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
  Image image(size.x, size.y);
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      // GL's row 0 is the bottom of the window.
      const std::uint8_t* pixel =
          &bytes[(static_cast<std::size_t>(size.y - 1 - y) * size.x + x) * 4];
      image.at(x, y) = glm::vec4(srgbToLinear(pixel[0] / 255.0f), srgbToLinear(pixel[1] / 255.0f),
                                 srgbToLinear(pixel[2] / 255.0f), 1.0f);
    }
  }
  return image;
}

// penumbra-0001.png, penumbra-0002.png, ...: the first name not taken in the working directory.
std::filesystem::path nextScreenshotPath() {
  for (int number = 1;; ++number) {
    char name[32];
    std::snprintf(name, sizeof(name), "penumbra-%04d.png", number);
    if (!std::filesystem::exists(name))
      return name;
  }
}

class Viewer {
 public:
  Viewer(Scene& scene, const ViewerOptions& options);
  ViewerSummary run();

 private:
  void handleInput(float seconds);
  void handleKeyPress(int key);
  void ensureRenderer(glm::ivec2 size);
  void reloadShaders(glm::ivec2 size);
  DebugViewSource currentView();
  glm::ivec2 pictureSize() const;
  void drawPanel(DebugViewSource& view, glm::ivec2 size);
  void drawViewSection(DebugViewSource& view);
  void saveScreenshot(const std::filesystem::path& file, glm::ivec2 size);

  Scene& scene_;
  const ViewerOptions& options_;
  Window window_;  // owns the GL context: declared first, so destroyed after every GL object
  gl::ContextInfo contextInfo_;
  DeviceProfile profile_;
  std::unique_ptr<DisplayPass> display_;
  std::unique_ptr<Renderer> renderer_;
  CameraController controller_;
  RenderSettings settings_;
  std::string viewName_;
  int level_;
  float exposure_;
  bool showHelp_;
  bool paused_ = false;
  bool renderPending_ = true;  // settings, camera or shaders changed since the last frame
  bool screenshotRequested_ = false;
  int animationFrame_ = 0;
  // Video textures follow the wall clock while the animation runs (it steps one frame/30 s per
  // rendered frame, however long the frame took); both stop while paused.
  double videoSeconds_ = 0.0;
  std::string shaderError_;
  std::string renderError_;
  std::string message_;
  std::map<std::string, glm::vec2> fittedRanges_;  // per view and level
  FrameTimeHistory frameTimes_;
};

Viewer::Viewer(Scene& scene, const ViewerOptions& options)
    : scene_(scene),
      options_(options),
      window_("penumbra view - " + scene.file.filename().string(),
              options.imageSize + glm::ivec2(kPanelWidth, 0)),
      contextInfo_(gl::queryContextInfo("glx")),
      profile_(deviceProfileFor(contextInfo_)),
      display_(std::make_unique<DisplayPass>()),
      controller_(scene.camera),
      settings_(options.settings),
      viewName_(options.view),
      level_(options.level),
      exposure_(options.exposure),
      showHelp_(options.showHelp) {
  std::fprintf(stderr, "penumbra: GL renderer %s, %s\npenumbra: device profile %s\n",
               contextInfo_.renderer.c_str(), contextInfo_.version.c_str(),
               describe(profile_).c_str());
}

void Viewer::handleInput(float seconds) {
  const ImGuiIO& io = ImGui::GetIO();
  const Camera before = controller_.camera();
  if (!io.WantCaptureMouse) {
    // The frame of the press leaves its delta out: on slow frames it holds the pointer's travel
    // before the button went down.
    const bool dragging = ImGui::IsMouseDown(0) && !ImGui::IsMouseClicked(0);
    if (dragging && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f))
      controller_.orbit({io.MouseDelta.x, io.MouseDelta.y}, pictureSize());
    if (io.MouseWheel != 0.0f)
      controller_.zoom(io.MouseWheel);
  }
  const std::vector<int> pressedKeys = window_.takePressedKeys();
  if (!io.WantCaptureKeyboard) {
    const auto axis = [this](int positiveKey, int negativeKey) {
      return (window_.keyDown(positiveKey) ? 1.0f : 0.0f) -
             (window_.keyDown(negativeKey) ? 1.0f : 0.0f);
    };
    const glm::vec3 axes(axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q),
                         axis(GLFW_KEY_W, GLFW_KEY_S));
    if (axes != glm::vec3(0.0f))
      controller_.fly(axes, seconds);
    for (const int key : pressedKeys)
      handleKeyPress(key);
  }
  const Camera& after = controller_.camera();
  if (after.position != before.position || after.target != before.target)
    renderPending_ = true;
}

void Viewer::handleKeyPress(int key) {
  switch (key) {
    case GLFW_KEY_R:
      controller_.reset();
      break;
    case GLFW_KEY_H:
      showHelp_ = !showHelp_;
      break;
    case GLFW_KEY_SPACE:
      paused_ = !paused_;
      break;
    case GLFW_KEY_P:
      screenshotRequested_ = true;
      break;
    case GLFW_KEY_F5:
      reloadShaders(pictureSize());
      break;
    case GLFW_KEY_ESCAPE:
      glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
      break;
    default:
      break;
  }
}

void Viewer::ensureRenderer(glm::ivec2 size) {
  if (renderer_ && renderer_->gbuffer().size == size)
    return;
  // The old renderer goes first: two full sets of targets need not fit at once.
  renderer_.reset();
  try {
    renderer_ = std::make_unique<Renderer>(scene_, size, profile_);
    renderPending_ = true;
  } catch (const RenderError& error) {
    renderError_ = error.what();
  }
}

void Viewer::reloadShaders(glm::ivec2 size) {
  // Every program is compiled when its pass is made, so a new renderer is a full reload; the old
  // one stays in use until the new one exists.
  try {
    auto display = std::make_unique<DisplayPass>();
    auto renderer = std::make_unique<Renderer>(scene_, size, profile_);
    display_ = std::move(display);
    renderer_ = std::move(renderer);
    shaderError_.clear();
    message_ = "shaders reloaded: " + gl::shaderOrigin();
    renderPending_ = true;
  } catch (const gl::ShaderError& error) {
    shaderError_ = error.what();
    message_ = "shader reload failed; the previous shaders stay in use";
  }
}

DebugViewSource Viewer::currentView() {
  const DebugViewInfo* info = findDebugView(viewName_);
  if (info == nullptr || !debugViewAvailable(*info, *renderer_, nullptr))
    info = findDebugView("radiance");
  DebugViewSource view = debugViewSource(*info, level_, *renderer_, settings_);
  if (view.fitRange) {
    const std::string key = std::string(info->name) + "@" + std::to_string(level_);
    auto fitted = fittedRanges_.find(key);
    if (fitted == fittedRanges_.end())
      fitted = fittedRanges_.emplace(key, valueRange(view)).first;
    view.range = fitted->second;
  }
  return view;
}

void Viewer::drawViewSection(DebugViewSource& view) {
  const DebugViewInfo* selected = findDebugView(viewName_);
  if (ImGui::BeginCombo("view", viewName_.c_str())) {
    for (const DebugViewInfo& info : debugViewInfos()) {
      const bool available = debugViewAvailable(info, *renderer_, nullptr);
      if (ImGui::Selectable(info.name, &info == selected,
                            available ? 0 : ImGuiSelectableFlags_Disabled))
        viewName_ = info.name;
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s%s", info.description, available ? "" : " (not in this frame)");
    }
    ImGui::EndCombo();
  }
  if (selected == nullptr)
    return;
  ImGui::TextWrapped("%s", selected->description);
  std::string why;
  if (!debugViewAvailable(*selected, *renderer_, &why)) {
    ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.3f, 1.0f), "%s; showing radiance", why.c_str());
  } else if (selected->indexed) {
    const glm::ivec2 indices = debugViewIndices(*selected, *renderer_);
    level_ = std::clamp(level_, indices.x, indices.y);
    ImGui::SliderInt(selected->needs == DebugViewNeeds::Shadows ? "slice" : "level", &level_,
                     indices.x, indices.y, "%d", ImGuiSliderFlags_AlwaysClamp);
  }
  if (view.kind == gpu::kDisplayRadiance)
    ImGui::SliderFloat("exposure", &exposure_, -10.0f, 10.0f, "%+.1f stops");
  const bool refit = drawLegend(view, exposure_);
  if (view.fitRange) {
    const std::string key = std::string(selected->name) + "@" + std::to_string(level_);
    fittedRanges_[key] = refit ? valueRange(view) : view.range;
  }
}

// The window's width less the panel's (at least a pixel, in a window narrower than the panel).
glm::ivec2 Viewer::pictureSize() const {
  const glm::ivec2 window = window_.framebufferSize();
  return {std::max(window.x - kPanelWidth, 1), window.y};
}

void Viewer::drawPanel(DebugViewSource& view, glm::ivec2 size) {
  // The column right of the picture, whatever the window's size.
  const glm::ivec2 window = window_.framebufferSize();
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(size.x), 0.0f));
  ImGui::SetNextWindowSize(
      ImVec2(static_cast<float>(std::max(window.x - size.x, 0)), static_cast<float>(window.y)));
  if (!ImGui::Begin("Penumbra", nullptr,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                        ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return;
  }
  // Widgets leave room on their right for labels as long as "visibility threshold".
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 11.0f);
  ImGui::Text("%s, %dx%d", scene_.file.filename().string().c_str(), size.x, size.y);
  ImGui::Text("frame %d (%.2f s), video %.2f s%s", animationFrame_,
              animationFrame_ / kFramesPerSecond, videoSeconds_, paused_ ? ", paused" : "");
  if (ImGui::Button(paused_ ? "resume" : "pause"))
    paused_ = !paused_;
  ImGui::SameLine();
  if (ImGui::Button("reset camera")) {
    controller_.reset();
    renderPending_ = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("reload shaders"))
    reloadShaders(size);
  ImGui::SameLine();
  if (ImGui::Button("screenshot"))
    screenshotRequested_ = true;
  const ImVec4 errorColour(1.0f, 0.45f, 0.4f, 1.0f);
  if (!message_.empty())
    ImGui::TextWrapped("%s", message_.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, errorColour);
  if (!shaderError_.empty())
    ImGui::TextWrapped("%s", shaderError_.c_str());
  if (!renderError_.empty())
    ImGui::TextWrapped("%s", renderError_.c_str());
  ImGui::PopStyleColor();

  ImGui::SetNextItemOpen(showHelp_);
  showHelp_ = ImGui::CollapsingHeader("help (H)");
  if (showHelp_)
    drawHelp();
  if (ImGui::CollapsingHeader("renderer", ImGuiTreeNodeFlags_DefaultOpen))
    renderPending_ |= drawSettingsPanel(settings_, size);
  if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen) && renderer_)
    drawViewSection(view);
  if (ImGui::CollapsingHeader("timing", ImGuiTreeNodeFlags_DefaultOpen) && renderer_) {
    ImGui::TextDisabled("%s", contextInfo_.renderer.c_str());
    drawTimings(renderer_->stageTimes(), renderer_->timingMethod(), frameTimes_);
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

void Viewer::saveScreenshot(const std::filesystem::path& file, glm::ivec2 size) {
  saveImage(readWindow(size), file);
  message_ = "saved " + file.string();
  std::fprintf(stderr, "penumbra: saved %s\n", file.string().c_str());
}

ViewerSummary Viewer::run() {
  ViewerSummary summary;
  std::vector<double> frameMilliseconds;
  std::vector<double> renderMilliseconds;
  std::map<StageKey, std::vector<double>> stageMilliseconds;
  Clock::time_point previousStart = Clock::now();
  bool idle = false;
  while (!window_.shouldClose()) {
    if (idle)
      glfwWaitEventsTimeout(kIdleWaitSeconds);
    else
      glfwPollEvents();
    const glm::ivec2 windowSize = window_.framebufferSize();
    const glm::ivec2 size = pictureSize();
    const Clock::time_point start = Clock::now();
    const float seconds = static_cast<float>(millisecondsBetween(previousStart, start) / 1000.0);
    previousStart = start;
    if (windowSize.x == 0 || windowSize.y == 0) {
      // Minimised: no framebuffer to draw into, so nothing is rendered until it comes back.
      idle = true;
      continue;
    }

    window_.beginFrame();
    if (options_.orbitFrames > 0 && summary.frames > 0) {
      controller_.turn(glm::two_pi<float>() / static_cast<float>(options_.orbitFrames));
      renderPending_ = true;
    }
    handleInput(seconds);
    if (!paused_ && summary.frames > 0)
      videoSeconds_ += seconds;
    ensureRenderer(size);
    const bool render = renderer_ && (renderPending_ || !paused_);
    if (render) {
      renderer_->setCamera(controller_.camera());
      try {
        renderer_->render(animationFrame_, settings_, videoSeconds_);
        renderError_.clear();
      } catch (const RenderError& error) {
        renderError_ = error.what();
      } catch (const gl::UniformError& error) {
        // A reloaded shader that lacks a uniform the renderer sets: shown like a compile error
        // until the next reload; automation ends with it (exit 4, docs/cli.md).
        if (options_.exitAfterFrames)
          throw;
        shaderError_ = error.what();
      }
      renderPending_ = false;
    }

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, windowSize.x, windowSize.y);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    DebugViewSource view;
    if (renderer_) {
      view = currentView();
      display_->draw(view, exposure_, size);
    }
    drawPanel(view, size);
    window_.drawInterface();

    ++summary.frames;
    summary.imageSize = size;
    const bool automationDone = options_.frames > 0 && summary.frames == options_.frames;
    if (automationDone && options_.screenshot)
      saveScreenshot(*options_.screenshot, windowSize);
    if (screenshotRequested_) {
      screenshotRequested_ = false;
      try {
        saveScreenshot(nextScreenshotPath(), windowSize);
      } catch (const ImageError& error) {
        message_ = error.what();
      }
    }
    window_.present();
    if (!paused_)
      ++animationFrame_;

    const double frameMs = millisecondsBetween(start, Clock::now());
    frameTimes_.add(frameMs);
    if (summary.frames > 1) {
      frameMilliseconds.push_back(frameMs);
      if (render) {
        renderMilliseconds.push_back(totalMilliseconds(renderer_->stageTimes()));
        for (const StageTime& stage : renderer_->stageTimes())
          stageMilliseconds[stage.key].push_back(stage.milliseconds);
      }
    }
    idle = !render;
    if (automationDone && options_.exitAfterFrames)
      break;
  }
  summary.medianFrameMs = median(frameMilliseconds);
  summary.medianRenderMs = median(renderMilliseconds);
  gl::drainErrors();
  summary.glErrors = gl::errorCount();
  summary.renderError = renderError_;
  if (renderer_) {
    for (const StageTime& stage : renderer_->stageTimes())
      summary.medianStages.push_back({stage.key, median(stageMilliseconds[stage.key])});
  }
  return summary;
}

}  // namespace

ViewerSummary runViewer(Scene& scene, const ViewerOptions& options) {
  // Hot reload is for editing the source tree's shaders, while the binary's tree is still there;
  // an installed or moved binary reloads its embedded copies.
  if (!gl::shaderDirectory() && std::filesystem::is_directory(gl::sourceShaderDirectory()))
    gl::setShaderDirectory(gl::sourceShaderDirectory());
  std::fprintf(stderr, "penumbra: view: %s (F5 reloads them)\n", gl::shaderOrigin().c_str());
  Viewer viewer(scene, options);
  return viewer.run();
}

}  // namespace penumbra::app
