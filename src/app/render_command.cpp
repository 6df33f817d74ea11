// `penumbra render`: a frame or a sequence of frames of a scene to EXR and/or PNG images or an
// MP4 video, in any renderer mode.

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/choice_option.h"
#include "app/command_failure.h"
#include "app/commands.h"
#include "app/progress.h"
#include "app/render_options.h"
#include "app/size_option.h"
#include "app/statistics_json.h"
#include "gl/context.h"
#include "gl/program.h"
#include "image/video_writer.h"
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
  std::string frames;  // FIRST:LAST, instead of `frame`
  std::string size;
  float exposure = 0.0f;
  Mode mode = Mode::Hierarchical;
  RenderSettings gpu;
  std::string debugView;
  std::vector<std::string> aovs;  // debug views stored as layers of the EXR outputs
  bool printStats = false;
  std::string statsJson;
  bool noShadows = false;
  int spp = 256;
  std::uint64_t seed = 1;
  int bounces = 0;
  bool quiet = false;  // no progress and no summary lines; warnings and errors still
};

std::atomic<bool> interrupted{false};

extern "C" void onInterrupt(int) {
  interrupted = true;
}

// The frames to render, inclusive: --frames FIRST:LAST, or the one --frame.
struct FrameRange {
  int first = 0;
  int last = 0;
  int count() const { return last - first + 1; }
};

FrameRange frameRangeOf(const RenderOptions& options) {
  if (options.frames.empty())
    return {options.frame, options.frame};
  const std::string& text = options.frames;
  const char* const end = text.data() + text.size();
  FrameRange range;
  const auto [colon, firstError] = std::from_chars(text.data(), end, range.first);
  bool valid = firstError == std::errc() && colon != end && *colon == ':';
  if (valid) {
    const auto [rest, lastError] = std::from_chars(colon + 1, end, range.last);
    valid = lastError == std::errc() && rest == end;
  }
  if (!valid || range.first < 0 || range.last < range.first) {
    throw CommandFailure{kExitUsage,
                         "--frames: expected FIRST:LAST with 0 <= FIRST <= LAST (e.g. 0:59), "
                         "found '" +
                             text + "'"};
  }
  return range;
}

// An image output named with one printf-style integer conversion for the frame number:
// %d, %4d (space padded) or %04d (zero padded).
struct FramePattern {
  std::string prefix;
  std::string suffix;
  std::size_t width = 0;
  bool zeroPadded = false;

  std::string pathOf(int frame) const {
    std::string number = std::to_string(frame);
    if (number.size() < width)
      number.insert(0, width - number.size(), zeroPadded ? '0' : ' ');
    return prefix + number + suffix;
  }
};

// The frame-number conversion of an output name; none when the name has no '%'. A '%' that is not
// the one conversion is a usage error.
std::optional<FramePattern> framePatternOf(const std::string& output) {
  const std::size_t percent = output.find('%');
  if (percent == std::string::npos)
    return std::nullopt;
  FramePattern pattern;
  std::size_t position = percent + 1;
  if (position < output.size() && output[position] == '0') {
    pattern.zeroPadded = true;
    ++position;
  }
  const std::size_t widthStart = position;
  while (position < output.size() && std::isdigit(static_cast<unsigned char>(output[position])))
    ++position;
  constexpr std::size_t kMaxWidthDigits = 2;
  if (position - widthStart > kMaxWidthDigits || position == output.size() ||
      output[position] != 'd' || output.find('%', position) != std::string::npos) {
    throw CommandFailure{kExitUsage, "-o " + output +
                                         ": expected one frame-number conversion such as %d or "
                                         "%04d, and no other '%'"};
  }
  if (position > widthStart)
    pattern.width = std::stoul(output.substr(widthStart, position - widthStart));
  pattern.prefix = output.substr(0, percent);
  pattern.suffix = output.substr(position + 1);
  return pattern;
}

void checkOutputs(const std::vector<std::string>& outputs, FrameRange frames) {
  for (const std::string& output : outputs) {
    const std::filesystem::path path(output);
    const std::string extension = path.extension().string();
    if (extension != ".exr" && extension != ".png" && extension != ".jpg" && extension != ".jpeg" &&
        extension != ".hdr" && !isVideoOutput(path)) {
      throw CommandFailure{kExitUsage, "-o " + output +
                                           ": unknown format; expected an image (.exr, .png, "
                                           ".jpg, .hdr) or a video (.mp4)"};
    }
    if (isVideoOutput(path) && output.find('%') != std::string::npos) {
      throw CommandFailure{kExitUsage, "-o " + output +
                                           ": a video holds every frame, so its name takes no "
                                           "frame number"};
    }
    if (!isVideoOutput(path) && !framePatternOf(output) && frames.count() > 1) {
      throw CommandFailure{kExitUsage,
                           "-o " + output + ": rendering " + std::to_string(frames.count()) +
                               " frames to images needs a frame-number pattern in the name, "
                               "e.g. " +
                               (path.parent_path() / path.stem()).string() + "_%04d" + extension};
    }
    const auto directory =
        path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    if (!std::filesystem::is_directory(directory)) {
      throw CommandFailure{
          kExitOutput, "-o " + output + ": directory " + directory.string() + " does not exist"};
    }
  }
}

// MP4 stores colour at half resolution (4:2:0), in blocks of 2x2 pixels.
void checkVideoSize(const std::vector<std::string>& outputs, glm::ivec2 size) {
  for (const std::string& output : outputs) {
    if (isVideoOutput(output) && (size.x % 2 != 0 || size.y % 2 != 0)) {
      throw CommandFailure{kExitUsage, "-o " + output +
                                           ": a video needs an even width and height; "
                                           "the image is " +
                                           std::to_string(size.x) + "x" + std::to_string(size.y) +
                                           " (see --size)"};
    }
  }
}

// Writes every rendered frame to each output: an image file per frame (named through its
// pattern, if it has one) or the next frame of a video.
class FrameOutputs {
 public:
  FrameOutputs(const std::vector<std::string>& outputs, glm::ivec2 size, float exposure) {
    save_.exposure = exposure;
    VideoOptions video;
    video.exposure = exposure;
    for (const std::string& output : outputs) {
      if (isVideoOutput(output))
        videos_.push_back(std::make_unique<VideoWriter>(output, size, video));
      else
        images_.push_back({output, framePatternOf(output)});
    }
  }

  // `layers` and `metadata` go into the EXR outputs (--aov); the others take the image alone.
  void write(int frame, const Image& image, const std::vector<ImageLayer>& layers = {},
             const ExrMetadata& metadata = {}) {
    for (const auto& [name, pattern] : images_) {
      const std::filesystem::path path = pattern ? pattern->pathOf(frame) : name;
      if (!layers.empty() && path.extension() == ".exr")
        saveLayeredExr(image, layers, metadata, path);
      else
        saveImage(image, path, save_);
    }
    for (const auto& video : videos_)
      video->write(image);
  }

  // Completes the videos; until then they exist only under temporary names.
  void finish() {
    for (const auto& video : videos_)
      video->finish();
  }

 private:
  std::vector<std::pair<std::string, std::optional<FramePattern>>> images_;
  std::vector<std::unique_ptr<VideoWriter>> videos_;
  SaveOptions save_;
};

RenderSettings gpuSettings(const RenderOptions& options) {
  RenderSettings settings = options.gpu;
  settings.mode = options.mode == Mode::Naive ? RenderMode::Naive : RenderMode::Hierarchical;
  settings.shadows.enabled = !options.noShadows;
  return settings;
}

ProgressStyle progressStyle(const RenderOptions& options, ProgressStyle style) {
  return options.quiet ? ProgressStyle::Silent : style;
}

// Receives each rendered frame, in order, with its AOV layers (--aov) and their metadata.
using FrameSink =
    std::function<void(int frame, const Image& image, const std::vector<ImageLayer>& layers,
                       const ExrMetadata& metadata)>;

// The header of an AOV EXR: the camera's matrices, and every setting of the frame.
ExrMetadata aovMetadata(const Renderer& renderer, const RenderSettings& settings, int frame,
                        const std::vector<std::string>& aovs) {
  const Camera& camera = renderer.camera();
  nlohmann::json cameraJson = {
      {"position", {camera.position.x, camera.position.y, camera.position.z}},
      {"target", {camera.target.x, camera.target.y, camera.target.z}},
      {"up", {camera.up.x, camera.up.y, camera.up.z}},
      {"fovy_degrees", camera.fovyDegrees},
      {"near", camera.nearPlane},
      {"far", camera.farPlane}};
  ExrMetadata metadata;
  metadata.matrices = {{"worldtocamera", camera.viewFromWorld()},
                       {"worldtoscreen", camera.clipFromView() * camera.viewFromWorld()},
                       {"penumbra:clipFromView", camera.clipFromView()}};
  std::string layers;
  for (const std::string& aov : aovs)
    layers += (layers.empty() ? "" : ",") + aov;
  metadata.strings = {{"penumbra:layers", layers},
                      {"penumbra:frame", std::to_string(frame)},
                      {"penumbra:camera", cameraJson.dump()},
                      {"penumbra:settings", renderSettingsJson(settings).dump()}};
  return metadata;
}

// One context and one renderer for every frame; the statistics are those of each frame in turn.
void renderOnGpu(Scene& scene, glm::ivec2 size, const RenderOptions& options, FrameRange frames,
                 const FrameSink& sink) {
  gl::HeadlessContext context;
  if (!options.quiet)
    std::fprintf(stderr, "penumbra: GL renderer %s\n", context.info().renderer.c_str());
  Renderer renderer(scene, size, deviceProfileFor(context.info()));
  if (options.printStats)
    std::fprintf(stderr, "device profile: %s\n", describe(renderer.deviceProfile()).c_str());
  const RenderSettings settings = gpuSettings(options);
  // --stats-json: one frame's object, or for a range an array of them with their frame numbers,
  // written once every frame has rendered.
  nlohmann::json statisticsPerFrame = nlohmann::json::array();
  // A range shows its progress on a terminal; a frame of the GPU modes takes too little time.
  // --stats prints a block per frame, which would break the bar's line.
  std::optional<ProgressReport> progress;
  if (frames.count() > 1 && !options.printStats)
    progress.emplace(renderModeName(settings.mode), progressStyle(options, ProgressStyle::BarOnly));
  for (int frame = frames.first; frame <= frames.last; ++frame) {
    renderer.render(frame, settings);
    if (options.printStats || !options.statsJson.empty()) {
      const FrameStatistics statistics = renderer.statistics();
      printStatistics(statistics, stderr);
      nlohmann::json entry = statisticsJson(statistics, settings);
      entry["frame"] = frame;
      entry["device_profile"] = deviceProfileJson(renderer.deviceProfile());
      statisticsPerFrame.push_back(entry);
    }
    std::vector<Image> aovImages;
    for (const std::string& aov : options.aovs) {
      aovImages.push_back(debugView(renderer, aov, settings));
      const Image& view = aovImages.back();
      if (view.width != size.x || view.height != size.y)
        throw CommandFailure{kExitUsage, "--aov " + aov + ": the view is " +
                                             std::to_string(view.width) + "x" +
                                             std::to_string(view.height) + ", not the image's " +
                                             std::to_string(size.x) + "x" + std::to_string(size.y) +
                                             "; only full-resolution views can be layers"};
    }
    const Image picture = options.debugView.empty()
                              ? renderer.readRadiance()
                              : debugView(renderer, options.debugView, settings);
    throwIfGlErrors();
    std::vector<ImageLayer> layers;
    for (std::size_t index = 0; index < aovImages.size(); ++index)
      layers.push_back({options.aovs[index], &aovImages[index]});
    sink(frame, picture, layers,
         options.aovs.empty() ? ExrMetadata()
                              : aovMetadata(renderer, settings, frame, options.aovs));
    if (progress) {
      const int done = frame - frames.first + 1;
      progress->update(static_cast<double>(done) / frames.count(),
                       "frame " + std::to_string(frame) + ", " + std::to_string(done) + " of " +
                           std::to_string(frames.count()));
    }
  }
  if (progress)
    progress->finish();
  if (!options.statsJson.empty()) {
    const nlohmann::json& written =
        frames.first == frames.last ? statisticsPerFrame.front() : statisticsPerFrame;
    writeTextFile(options.statsJson, written.dump(2) + "\n");
  }
}

Image renderOnCpu(const Scene& scene, glm::ivec2 size, const RenderOptions& options) {
  ReferenceSettings settings;
  settings.sampling = options.mode == Mode::Reference ? ReferenceSettings::Sampling::Stratified
                                                      : ReferenceSettings::Sampling::Vpl;
  settings.samplesPerPixel = options.spp;
  settings.vplsPerLight = options.gpu.vplsPerLight;
  settings.seed = options.seed;
  settings.shadows = !options.noShadows;
  settings.bounces = options.bounces;
  settings.frame = options.frame;
  settings.size = size;
  settings.cancel = &interrupted;
  ProgressReport progress(options.mode == Mode::Reference ? "reference" : "reference-vpl",
                          progressStyle(options, ProgressStyle::BarOrLines));
  settings.progress = [&progress](double fraction) { progress.update(fraction); };
  const auto previous = std::signal(SIGINT, onInterrupt);
  try {
    ReferenceStats stats;
    Image image = renderReference(scene, settings, &stats);
    std::signal(SIGINT, previous);
    progress.finish();
    if (!options.quiet) {
      std::fprintf(stderr, "penumbra: %.3g rays in %.2f s (%.3g rays/s)\n",
                   static_cast<double>(stats.raysTraced), stats.seconds,
                   static_cast<double>(stats.raysTraced) / std::max(stats.seconds, 1e-9));
    }
    return image;
  } catch (const Cancelled&) {
    std::signal(SIGINT, previous);
    progress.finish();
    throw CommandFailure{kExitInterrupted, "interrupted; no output written"};
  }
}

int runRender(const RenderOptions& options) {
  try {
    const FrameRange frames = frameRangeOf(options);
    checkOutputs(options.outputs, frames);
    if (options.mode == Mode::Hierarchical || options.mode == Mode::Naive)
      validate(gpuSettings(options));
    else
      cellsPerSideFor(options.gpu.vplsPerLight);
    if (!options.debugView.empty() && options.mode != Mode::Hierarchical &&
        options.mode != Mode::Naive)
      throw CommandFailure{kExitUsage, "--debug-view needs a GPU mode (hierarchical or naive)"};
    if (!options.aovs.empty()) {
      if (options.mode != Mode::Hierarchical && options.mode != Mode::Naive)
        throw CommandFailure{kExitUsage, "--aov needs a GPU mode (hierarchical or naive)"};
      if (!options.debugView.empty())
        throw CommandFailure{kExitUsage, "--aov and --debug-view: choose one"};
      const bool anyExr = std::any_of(options.outputs.begin(), options.outputs.end(),
                                      [](const std::string& output) {
                                        return std::filesystem::path(output).extension() == ".exr";
                                      });
      if (!anyExr)
        throw CommandFailure{kExitUsage, "--aov: the layers are written to .exr outputs; add one"};
    }
    if (options.spp < 1)
      throw CommandFailure{kExitUsage, "--spp must be at least 1"};
    if (options.bounces > 0 && (options.mode == Mode::Hierarchical || options.mode == Mode::Naive))
      throw CommandFailure{kExitUsage,
                           "--bounces is for the reference modes; the GPU modes take --indirect"};

    const auto start = std::chrono::steady_clock::now();
    Scene scene = loadScene(parseSceneFile(options.scene));
    // Every renderer mode lights surfaces only through area lights (quads and emissive meshes),
    // so the image would be black.
    if (scene.lights.empty()) {
      throw SceneError({options.scene, 0, 0},
                       "the scene has no area_light and no emissive mesh, so nothing would be lit; "
                       "add an area_light block or give an object a material with 'emit' "
                       "(docs/scene-format.md)");
    }
    for (const std::string& warning : scene.warnings)
      std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    const glm::ivec2 size =
        options.size.empty() ? scene.camera.size : *parseImageSize(options.size);

    checkVideoSize(options.outputs, size);

    FrameOutputs outputs(options.outputs, size, options.exposure);
    const FrameSink sink =
        [&outputs](int frame, const Image& image, const std::vector<ImageLayer>& layers,
                   const ExrMetadata& metadata) { outputs.write(frame, image, layers, metadata); };
    if (options.mode == Mode::Hierarchical || options.mode == Mode::Naive) {
      renderOnGpu(scene, size, options, frames, sink);
    } else {
      for (int frame = frames.first; frame <= frames.last; ++frame) {
        RenderOptions oneFrame = options;
        oneFrame.frame = frame;
        sink(frame, renderOnCpu(scene, size, oneFrame), {}, {});
      }
    }
    outputs.finish();
    if (!options.quiet) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "penumbra: rendered %s (%dx%d, %d frame%s) in %.2f s\n",
                   options.scene.c_str(), size.x, size.y, frames.count(),
                   frames.count() == 1 ? "" : "s", seconds);
    }
    return kExitOk;
  } catch (...) {
    return reportFailure();
  }
}

}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* render =
      app.add_subcommand("render", "Render a frame or a sequence of a scene to images or a video");
  render->add_option("scene", options->scene, "Scene file (default: the built-in demo)");
  render
      ->add_option("-o,--output", options->outputs,
                   "Output image or video; repeat for several (.exr linear, .png tone-mapped, "
                   ".mp4 tone-mapped video)")
      ->required();
  CLI::Option* frame =
      render->add_option("--frame", options->frame, "Frame number (time = frame / 30 s)")
          ->check(CLI::NonNegativeNumber);
  render
      ->add_option("--frames", options->frames,
                   "Frames FIRST:LAST, inclusive; images need a pattern (-o out_%04d.png), "
                   "a .mp4 output takes them all")
      ->excludes(frame);
  render->add_option("--size", options->size, "Image size WIDTHxHEIGHT (default: the camera's)")
      ->check(imageSizeValidator());
  render->add_option("--exposure", options->exposure,
                     "Exposure in stops for 8-bit outputs (value * 2^E)");
  addChoiceOption<Mode>(*render, "--mode", options->mode,
                        {{"hierarchical", Mode::Hierarchical},
                         {"naive", Mode::Naive},
                         {"reference", Mode::Reference},
                         {"reference-vpl", Mode::ReferenceVpl}},
                        "Renderer: the GPU modes hierarchical and naive, the CPU modes reference "
                        "and reference-vpl");
  addRenderSettingsOptions(*render, options->gpu);
  render->add_option("--debug-view", options->debugView,
                     "Write an intermediate buffer instead of the image (docs/cli.md), one of: " +
                         debugViewNameList() + " (-N: the level or slice)");
  render
      ->add_option("--aov", options->aovs,
                   "Also store these debug views (e.g. albedo,normal,depth,levels) as layers of "
                   "each .exr output, with the camera and settings in its header")
      ->delimiter(',');
  render->add_flag(
      "--stats", options->printStats,
      "Print the samples gathered per level and, with shadows, the shadow rays traced");
  render->add_option("--stats-json", options->statsJson, "Write the statistics as JSON");
  render->add_flag("--no-shadows", options->noShadows, "Every VPL or light sample is visible");
  render->add_flag("--quiet", options->quiet,
                   "No progress and no summary on stderr (warnings and errors still)");
  render->add_option("--spp", options->spp, "reference: light samples per pixel and light");
  render->add_option("--seed", options->seed, "reference: random seed");
  render
      ->add_option("--bounces", options->bounces,
                   "reference modes: 1 adds one path-traced diffuse bounce (--spp rays per "
                   "pixel); compare with the GPU modes' --indirect")
      ->check(CLI::Range(0, 1));
  render->final_callback([options, &exitCode] { exitCode = runRender(*options); });
}

}  // namespace penumbra::app
