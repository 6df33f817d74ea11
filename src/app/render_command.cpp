// `penumbra render`: one frame of a scene to EXR and/or PNG, in any renderer mode.

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/progress.h"
#include "app/statistics_json.h"
#include "gl/context.h"
#include "gl/program.h"
#include "reference/reference.h"
#include "render/debug_views.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace penumbra::app {
namespace {

enum class Mode { Hierarchical, Naive, Reference, ReferenceVpl };

struct RenderOptions {
  std::string scene = PENUMBRA_DEMO_SCENE;
  std::vector<std::string> outputs;
  int frame = 0;
  std::string size;
  int vpls = 256;
  float exposure = 0.0f;
  Mode mode = Mode::Hierarchical;
  MultiresolutionSettings multiresolution;
  std::string debugView;
  bool printStats = false;
  std::string statsJson;
  bool noShadows = false;
  int spp = 256;
  std::uint64_t seed = 1;
};

std::atomic<bool> interrupted{false};

extern "C" void onInterrupt(int) {
  interrupted = true;
}

// Thrown with the exit code that a failure of this kind maps to.
struct CommandFailure {
  int exitCode;
  std::string message;
};

glm::ivec2 parseSize(const std::string& text) {
  int width = 0;
  int height = 0;
  char separator = 0;
  char trailing = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &separator, &height, &trailing) != 3 ||
      separator != 'x' || width < 1 || height < 1) {
    throw CommandFailure{kExitUsage,
                         "--size: expected WIDTHxHEIGHT with positive integers "
                         "(e.g. 512x512), found '" +
                             text + "'"};
  }
  return {width, height};
}

void checkOutputs(const std::vector<std::string>& outputs) {
  for (const std::string& output : outputs) {
    const std::filesystem::path path(output);
    const std::string extension = path.extension().string();
    if (extension != ".exr" && extension != ".png" && extension != ".jpg" && extension != ".jpeg" &&
        extension != ".hdr") {
      throw CommandFailure{kExitUsage, "-o " + output +
                                           ": unknown image format; expected .exr, .png, .jpg "
                                           "or .hdr"};
    }
    const auto directory =
        path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    if (!std::filesystem::is_directory(directory)) {
      throw CommandFailure{
          kExitOutput, "-o " + output + ": directory " + directory.string() + " does not exist"};
    }
  }
}

RenderSettings gpuSettings(const RenderOptions& options) {
  RenderSettings settings;
  settings.mode = options.mode == Mode::Naive ? RenderMode::Naive : RenderMode::Hierarchical;
  settings.vplsPerLight = options.vpls;
  settings.multiresolution = options.multiresolution;
  return settings;
}

Image renderOnGpu(Scene& scene, glm::ivec2 size, const RenderOptions& options) {
  gl::HeadlessContext context;
  std::fprintf(stderr, "penumbra: GL renderer %s\n", context.info().renderer.c_str());
  if (!options.noShadows) {
    std::fprintf(stderr,
                 "penumbra: warning: the GPU modes do not compute shadows yet; every VPL counts "
                 "as visible (as with --no-shadows)\n");
  }
  Renderer renderer(scene, size);
  const RenderSettings settings = gpuSettings(options);
  renderer.render(options.frame, settings);
  if (options.printStats || !options.statsJson.empty()) {
    const FrameStatistics statistics = renderer.statistics();
    printStatistics(statistics, stderr);
    if (!options.statsJson.empty())
      writeTextFile(options.statsJson, statisticsJson(statistics, settings).dump(2) + "\n");
  }
  return options.debugView.empty() ? renderer.readRadiance()
                                   : debugView(renderer, options.debugView, settings);
}

Image renderOnCpu(const Scene& scene, glm::ivec2 size, const RenderOptions& options) {
  ReferenceSettings settings;
  settings.sampling = options.mode == Mode::Reference ? ReferenceSettings::Sampling::Stratified
                                                      : ReferenceSettings::Sampling::Vpl;
  settings.samplesPerPixel = options.spp;
  settings.vplsPerLight = options.vpls;
  settings.seed = options.seed;
  settings.shadows = !options.noShadows;
  settings.frame = options.frame;
  settings.size = size;
  settings.cancel = &interrupted;
  ProgressReport progress(options.mode == Mode::Reference ? "reference" : "reference-vpl");
  settings.progress = [&progress](double fraction) { progress.update(fraction); };
  const auto previous = std::signal(SIGINT, onInterrupt);
  try {
    ReferenceStats stats;
    Image image = renderReference(scene, settings, &stats);
    std::signal(SIGINT, previous);
    progress.finish();
    std::fprintf(stderr, "penumbra: %.3g rays in %.2f s (%.3g rays/s)\n",
                 static_cast<double>(stats.raysTraced), stats.seconds,
                 static_cast<double>(stats.raysTraced) / std::max(stats.seconds, 1e-9));
    return image;
  } catch (const Cancelled&) {
    std::signal(SIGINT, previous);
    progress.finish();
    throw CommandFailure{kExitInterrupted, "interrupted; no output written"};
  }
}

int runRender(const RenderOptions& options) {
  try {
    checkOutputs(options.outputs);
    if (options.mode == Mode::Hierarchical || options.mode == Mode::Naive)
      validate(gpuSettings(options));
    else
      cellsPerSideFor(options.vpls);
    if (!options.debugView.empty() && options.mode != Mode::Hierarchical &&
        options.mode != Mode::Naive)
      throw CommandFailure{kExitUsage, "--debug-view needs a GPU mode (hierarchical or naive)"};
    if (options.spp < 1)
      throw CommandFailure{kExitUsage, "--spp must be at least 1"};

    const auto start = std::chrono::steady_clock::now();
    Scene scene = loadScene(parseSceneFile(options.scene));
    for (const std::string& warning : scene.warnings)
      std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    const glm::ivec2 size = options.size.empty() ? scene.camera.size : parseSize(options.size);

    const bool onGpu = options.mode == Mode::Hierarchical || options.mode == Mode::Naive;
    const Image image =
        onGpu ? renderOnGpu(scene, size, options) : renderOnCpu(scene, size, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    SaveOptions save;
    save.exposure = options.exposure;
    for (const std::string& output : options.outputs)
      saveImage(image, output, save);
    std::fprintf(stderr, "penumbra: rendered %s (%dx%d) in %.2f s\n", options.scene.c_str(), size.x,
                 size.y, seconds);
    return kExitOk;
  } catch (const CommandFailure& failure) {
    std::fprintf(stderr, "penumbra: error: %s\n", failure.message.c_str());
    return failure.exitCode;
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  } catch (const gl::ContextError& error) {
    std::fprintf(stderr, "penumbra: error: %s\n", error.what());
    return kExitGpu;
  } catch (const gl::ShaderError& error) {
    std::fprintf(stderr, "penumbra: error: %s\n", error.what());
    return kExitGpu;
  } catch (const RenderError& error) {
    std::fprintf(stderr, "penumbra: error: %s\n", error.what());
    return kExitUsage;
  } catch (const ImageError& error) {
    std::fprintf(stderr, "penumbra: error: %s\n", error.what());
    return kExitOutput;
  } catch (const OutputError& error) {
    std::fprintf(stderr, "penumbra: error: %s\n", error.what());
    return kExitOutput;
  }
}

}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* render = app.add_subcommand("render", "Render one frame of a scene to EXR and/or PNG");
  render->add_option("scene", options->scene, "Scene file (default: the built-in demo)")
      ->check(CLI::ExistingFile);
  render
      ->add_option("-o,--output", options->outputs,
                   "Output image; repeat for several (.exr linear, .png tone-mapped)")
      ->required();
  render->add_option("--frame", options->frame, "Frame number (time = frame / 30 s)")
      ->check(CLI::NonNegativeNumber);
  render->add_option("--size", options->size, "Image size WIDTHxHEIGHT (default: the camera's)");
  render->add_option("--vpls", options->vpls, "VPLs per light: a square number, 1 to 1024");
  render->add_option("--exposure", options->exposure,
                     "Exposure in stops for 8-bit outputs (value * 2^E)");
  const std::map<std::string, Mode> modes{{"hierarchical", Mode::Hierarchical},
                                          {"naive", Mode::Naive},
                                          {"reference", Mode::Reference},
                                          {"reference-vpl", Mode::ReferenceVpl}};
  render
      ->add_option("--mode", options->mode,
                   "Renderer: hierarchical (default), naive, reference, reference-vpl")
      ->transform(CLI::CheckedTransformer(modes, CLI::ignore_case));
  MultiresolutionSettings& multiresolution = options->multiresolution;
  render
      ->add_option("--coarsest", multiresolution.coarsestSize,
                   "hierarchical: larger side of the coarsest level, in texels")
      ->capture_default_str();
  render
      ->add_option("--depth-threshold", multiresolution.depthThreshold,
                   "hierarchical: refine where |grad z|/z times the image size exceeds this")
      ->capture_default_str();
  render
      ->add_option("--normal-threshold", multiresolution.normalThreshold,
                   "hierarchical: refine where |N1 - N2| between neighbours exceeds this")
      ->capture_default_str();
  render
      ->add_option("--plane-tolerance", multiresolution.planeTolerance,
                   "hierarchical: upsampling trusts coarser texels this close to the plane "
                   "(fraction of the distance to the eye)")
      ->capture_default_str();
  render->add_option("--debug-view", options->debugView,
                     "Write an intermediate buffer instead of the image (docs/multiresolution.md)");
  render->add_flag("--stats", options->printStats, "Print the samples gathered per level");
  render->add_option("--stats-json", options->statsJson, "Write the statistics as JSON");
  render->add_flag("--no-shadows", options->noShadows, "Every VPL or light sample is visible");
  render->add_option("--spp", options->spp, "reference: light samples per pixel and light");
  render->add_option("--seed", options->seed, "reference: random seed");
  render->final_callback([options, &exitCode] { exitCode = runRender(*options); });
}

}  // namespace penumbra::app
