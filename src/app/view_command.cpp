// `penumbra view`: the interactive viewer (src/app/viewer/), and its automation for tests and
// scripts (--frames N --screenshot FILE --exit).

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/choice_option.h"
#include "app/command_failure.h"
#include "app/commands.h"
#include "app/render_options.h"
#include "app/size_option.h"
#include "app/viewer/viewer.h"
#include "gl/context.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/debug_view_registry.h"
#include "scene/scene.h"

namespace penumbra::app {
namespace {

struct ViewCommandOptions {
  std::string scene = PENUMBRA_DEMO_SCENE;
  std::string size;
  std::string screenshot;
  bool hideHelp = false;
  bool noShadows = false;
  ViewerOptions viewer;
};

void checkScreenshotPath(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  if (extension != ".png" && extension != ".jpg" && extension != ".jpeg") {
    throw CommandFailure{kExitUsage, "--screenshot " + path.string() +
                                         ": unknown image format; expected .png or .jpg"};
  }
  const std::filesystem::path directory =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  if (!std::filesystem::is_directory(directory)) {
    throw CommandFailure{kExitOutput, "--screenshot " + path.string() + ": directory " +
                                          directory.string() + " does not exist"};
  }
}

int runView(ViewCommandOptions& options) {
  ViewerOptions& viewer = options.viewer;
  try {
    viewer.settings.shadows.enabled = !options.noShadows;
    validate(viewer.settings);
    if (findDebugView(viewer.view) == nullptr) {
      throw CommandFailure{kExitUsage, "--debug-view: unknown view '" + viewer.view +
                                           "'; expected one of: " + debugViewNameList()};
    }
    if (!options.screenshot.empty()) {
      checkScreenshotPath(options.screenshot);
      viewer.screenshot = options.screenshot;
    }
    viewer.showHelp = !options.hideHelp;

    Scene scene = loadScene(parseSceneFile(options.scene));
    for (const std::string& warning : scene.warnings)
      std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    viewer.imageSize = options.size.empty() ? scene.camera.size : *parseImageSize(options.size);

    const ViewerSummary summary = runViewer(scene, viewer);
    const std::string camera =
        viewer.orbitFrames > 0
            ? ", the camera turning 1/" + std::to_string(viewer.orbitFrames) + " of a turn a frame"
            : "";
    std::fprintf(stderr,
                 "penumbra: view: %d frames at %dx%d%s; median frame time %.1f ms, of which the "
                 "render passes take %.1f ms (first frame left out)\n",
                 summary.frames, summary.imageSize.x, summary.imageSize.y, camera.c_str(),
                 summary.medianFrameMs, summary.medianRenderMs);
    for (const StageTime& stage : summary.medianStages)
      std::fprintf(stderr, "penumbra: view:   %-14s %8.1f ms\n", stageLabel(stage.key).c_str(),
                   stage.milliseconds);
    if (viewer.exitAfterFrames && !summary.renderError.empty()) {
      std::fprintf(stderr, "penumbra: error: %s\n", summary.renderError.c_str());
      return kExitUsage;
    }
    if (summary.glErrors > 0)
      throw glErrorsFailure(summary.glErrors);
    return kExitOk;
  } catch (...) {
    return reportFailure();
  }
}

}  // namespace

void addViewCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<ViewCommandOptions>();
  ViewerOptions& viewer = options->viewer;
  CLI::App* view = app.add_subcommand("view", "Open a scene in the interactive viewer");
  view->add_option("scene", options->scene, "Scene file (default: the built-in demo)");
  view->add_option("--size", options->size,
                   "Picture size WIDTHxHEIGHT (default: the camera's); the panel is beside it")
      ->check(imageSizeValidator());
  addChoiceOption<RenderMode>(
      *view, "--mode", viewer.settings.mode,
      {{"hierarchical", RenderMode::Hierarchical}, {"naive", RenderMode::Naive}}, "Renderer");
  addRenderSettingsOptions(*view, viewer.settings);
  view->add_flag("--no-shadows", options->noShadows, "Start with shadows off");
  view->add_option("--debug-view", viewer.view,
                   "The view shown first (docs/viewer.md): " + debugViewNameList())
      ->capture_default_str();
  view->add_option("--level", viewer.level,
                   "Pyramid level (or voxel slice) of an indexed view, the -N of render's names")
      ->check(CLI::NonNegativeNumber);
  view->add_option("--exposure", viewer.exposure, "Exposure in stops (value * 2^E)");
  view->add_flag("--no-help", options->hideHelp, "Start without the help overlay");
  CLI::Option* frames =
      view->add_option("--frames", viewer.frames,
                       "Automation: after this many frames, save --screenshot and obey --exit")
          ->check(CLI::PositiveNumber);
  view->add_option("--screenshot", options->screenshot,
                   "Automation: save the window (.png or .jpg) after --frames frames")
      ->needs(frames);
  view->add_flag("--exit", viewer.exitAfterFrames, "Automation: quit after --frames frames")
      ->needs(frames);
  view->add_option("--orbit", viewer.orbitFrames,
                   "Automation: turn the camera about its target by 1/N of a turn every frame "
                   "after the first, to time frames with the camera moving")
      ->check(CLI::PositiveNumber);
  view->final_callback([options, &exitCode] { exitCode = runView(*options); });
}

}  // namespace penumbra::app
