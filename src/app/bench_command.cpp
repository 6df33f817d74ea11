// `penumbra bench`: time per pass of the GPU renderer modes (median and spread over several
// frames after a warm-up, at a fixed view or along an orbit), their samples per level, and naive
// against hierarchical: speed ratios and the image difference. JSON schema: docs/bench.md.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/command_failure.h"
#include "app/commands.h"
#include "app/progress.h"
#include "app/render_options.h"
#include "app/size_option.h"
#include "app/statistics_json.h"
#include "gl/context.h"
#include "gl/program.h"
#include "image/metrics.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace penumbra::app {
namespace {

struct BenchOptions {
  std::string scene = PENUMBRA_DEMO_SCENE;
  std::string size;
  int frame = 0;
  int frames = 10;
  int warmup = 2;
  int orbit = 0;  // frames of one turn of the camera about its target; 0: a fixed view
  std::vector<std::string> modes = {"hierarchical", "naive"};
  RenderSettings gpu;  // the mode is set per run
  bool noShadows = false;
  std::string json;
};

// The requested modes in order, each once.
std::vector<RenderMode> parseModes(const std::vector<std::string>& names) {
  std::vector<RenderMode> modes;
  for (const std::string& name : names) {
    RenderMode mode = RenderMode::Hierarchical;
    if (name == "naive")
      mode = RenderMode::Naive;
    else if (name != "hierarchical")
      throw CommandFailure{kExitUsage,
                           "--modes: unknown mode '" + name + "'; expected hierarchical or naive"};
    if (std::find(modes.begin(), modes.end(), mode) == modes.end())
      modes.push_back(mode);
  }
  if (modes.empty())
    throw CommandFailure{kExitUsage, "--modes: expected at least one of hierarchical, naive"};
  return modes;
}

// Median, quartiles (linear interpolation between order statistics, numpy's default) and range.
struct Spread {
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
  double firstQuartile = 0.0;
  double thirdQuartile = 0.0;
  double interquartileRange() const { return thirdQuartile - firstQuartile; }
};

Spread spreadOf(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const auto quantile = [&values](double fraction) {
    const double position = fraction * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, values.size() - 1);
    return values[below] +
           (position - static_cast<double>(below)) * (values[above] - values[below]);
  };
  return {quantile(0.5), values.front(), values.back(), quantile(0.25), quantile(0.75)};
}

nlohmann::json spreadJson(const Spread& spread, const std::vector<double>& samples) {
  return {{"median", spread.median},    {"min", spread.min},
          {"max", spread.max},          {"q1", spread.firstQuartile},
          {"q3", spread.thirdQuartile}, {"iqr", spread.interquartileRange()},
          {"samples", samples}};
}

// One measured frame: where the camera was, each pass's time, and the samples per level.
struct FrameRecord {
  int sceneFrame = 0;
  double orbitDegrees = 0.0;
  std::vector<StageTime> passes;
  FrameStatistics statistics;
};

// The measurements of one mode: each pass's time per measured frame, in the order passes ran.
struct ModeResult {
  RenderMode mode = RenderMode::Hierarchical;
  RenderSettings settings;
  std::vector<StageKey> passes;
  std::map<StageKey, std::vector<double>> passMilliseconds;
  std::vector<double> frameMilliseconds;     // sum of the passes
  std::vector<double> lightingMilliseconds;  // frame minus the passes every mode shares
  std::vector<double> gatherMilliseconds;    // the gather of every level
  // Per level (index 0 at full resolution), the sum of the passes that ran at that level.
  std::vector<std::vector<double>> levelMilliseconds;
  std::vector<FrameRecord> frameRecords;
  FrameStatistics statistics;
  Image radiance;

  std::optional<Spread> passSpread(StageKey pass) const {
    const auto found = passMilliseconds.find(pass);
    if (found == passMilliseconds.end())
      return std::nullopt;
    return spreadOf(found->second);
  }
};

ModeResult runMode(Renderer& renderer, const Camera& start, RenderMode mode,
                   const BenchOptions& options) {
  ModeResult result;
  result.mode = mode;
  result.settings = options.gpu;
  result.settings.mode = mode;
  result.settings.shadows.enabled = !options.noShadows;
  const int total = options.warmup + options.frames;
  ProgressReport progress(std::string("bench ") + renderModeName(mode));
  for (int i = 0; i < total; ++i) {
    progress.update(static_cast<double>(i) / total);
    // Along an orbit, measured frames are 1/orbit of a turn apart, centred on the scene's
    // camera (fewer frames than `orbit` cover an arc), and measured frame m renders scene frame
    // frame + m (animation and video advance with it); the warm-up frames render the first
    // from one step before the first measured frame's camera, so that every measured frame's
    // camera moved and none keeps the last frame's masks.
    const int step = options.orbit > 0 ? std::max(i - options.warmup, -1) : 0;
    const double degrees =
        options.orbit > 0 ? 360.0 * (step - 0.5 * (options.frames - 1)) / options.orbit : 0.0;
    renderer.setCamera(start.turnedAboutTarget(static_cast<float>(glm::radians(degrees))));
    renderer.render(options.frame + std::max(step, 0), result.settings);
    if (i < options.warmup)
      continue;
    double frame = 0.0;
    double lighting = 0.0;
    double gather = 0.0;
    std::vector<double> levels;
    for (const StageTime& time : renderer.stageTimes()) {
      if (!result.passMilliseconds.contains(time.key))
        result.passes.push_back(time.key);
      result.passMilliseconds[time.key].push_back(time.milliseconds);
      frame += time.milliseconds;
      if (!isSharedStage(time.key.stage))
        lighting += time.milliseconds;
      if (time.key.stage == Stage::Gather)
        gather += time.milliseconds;
      if (time.key.level != StageKey::kNoLevel) {
        const auto level = static_cast<std::size_t>(time.key.level);
        levels.resize(std::max(levels.size(), level + 1));
        levels[level] += time.milliseconds;
      }
    }
    result.frameMilliseconds.push_back(frame);
    result.lightingMilliseconds.push_back(lighting);
    result.gatherMilliseconds.push_back(gather);
    result.levelMilliseconds.resize(std::max(result.levelMilliseconds.size(), levels.size()));
    for (std::size_t level = 0; level < levels.size(); ++level)
      result.levelMilliseconds[level].push_back(levels[level]);
    result.frameRecords.push_back(
        {options.frame + step, degrees, renderer.stageTimes(), renderer.statistics()});
  }
  progress.update(1.0);
  progress.finish();
  result.statistics = result.frameRecords.back().statistics;  // --frames is at least 1
  result.radiance = renderer.readRadiance();
  return result;
}

// The passes of every mode in one order: each pass after the pass that preceded it in its mode.
std::vector<StageKey> mergedPassOrder(const std::vector<ModeResult>& results) {
  std::vector<StageKey> order;
  for (const ModeResult& result : results) {
    auto insertAt = order.begin();
    for (const StageKey& pass : result.passes) {
      const auto found = std::find(order.begin(), order.end(), pass);
      insertAt = found != order.end() ? found + 1 : order.insert(insertAt, pass) + 1;
    }
  }
  return order;
}

// The shortest decimal that reads back as the same float (0.1f as 0.1, not 0.10000000149).
double shortestDecimal(float value) {
  for (int digits = 6; digits < 9; ++digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value)
      return std::strtod(text, nullptr);
  }
  return static_cast<double>(value);
}

std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.starts_with("model name")) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos && colon + 2 <= line.size())
        return line.substr(colon + 2);
    }
  }
  return "unknown";
}

std::string utcDate() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// What naive against hierarchical gives, when both ran.
struct Comparison {
  double gatherSpeedup = 0.0;    // naive gather time / hierarchical gather time (medians)
  double lightingSpeedup = 0.0;  // the same for the lighting time
  double idealSpeedup = 0.0;     // full-resolution samples / samples gathered
  ImageMetrics metrics;          // hierarchical against naive
};

std::optional<Comparison> compareModes(const std::vector<ModeResult>& results) {
  const ModeResult* hierarchical = nullptr;
  const ModeResult* naive = nullptr;
  for (const ModeResult& result : results)
    (result.mode == RenderMode::Naive ? naive : hierarchical) = &result;
  if (hierarchical == nullptr || naive == nullptr)
    return std::nullopt;
  Comparison comparison;
  const auto ratio = [](double numerator, double denominator) {
    return denominator > 0.0 ? numerator / denominator : 0.0;
  };
  comparison.gatherSpeedup = ratio(spreadOf(naive->gatherMilliseconds).median,
                                   spreadOf(hierarchical->gatherMilliseconds).median);
  comparison.lightingSpeedup = ratio(spreadOf(naive->lightingMilliseconds).median,
                                     spreadOf(hierarchical->lightingMilliseconds).median);
  comparison.idealSpeedup = ratio(hierarchical->statistics.fullResolutionSamples,
                                  hierarchical->statistics.samplesGathered());
  comparison.metrics = compareImages(hierarchical->radiance, naive->radiance);
  return comparison;
}

struct Environment {
  gl::ContextInfo gl;
  std::string scene;
  glm::ivec2 size{0};
  int lightCount = 0;
};

nlohmann::json benchJson(const BenchOptions& options, const Environment& environment,
                         const DeviceProfile& profile, const std::vector<ModeResult>& results,
                         const std::optional<Comparison>& comparison) {
  nlohmann::json modes = nlohmann::json::object();
  for (const ModeResult& result : results) {
    nlohmann::json passes = nlohmann::json::array();
    nlohmann::json passMedians = nlohmann::json::object();
    for (const StageKey& pass : result.passes) {
      const std::vector<double>& samples = result.passMilliseconds.at(pass);
      const Spread spread = spreadOf(samples);
      nlohmann::json entry = spreadJson(spread, samples);
      entry["pass"] = stageLabel(pass);
      entry["shared"] = isSharedStage(pass.stage);
      passes.push_back(entry);
      passMedians[stageLabel(pass)] = spread.median;
    }
    nlohmann::json levels = nlohmann::json::array();
    for (const std::vector<double>& samples : result.levelMilliseconds)
      levels.push_back(spreadJson(spreadOf(samples), samples));
    const Spread frame = spreadOf(result.frameMilliseconds);
    const Spread lighting = spreadOf(result.lightingMilliseconds);
    const Spread gather = spreadOf(result.gatherMilliseconds);
    nlohmann::json frameRecords = nlohmann::json::array();
    for (std::size_t i = 0; i < result.frameRecords.size(); ++i) {
      const FrameRecord& record = result.frameRecords[i];
      nlohmann::json recordPasses = nlohmann::json::object();
      for (const StageTime& time : record.passes)
        recordPasses[stageLabel(time.key)] = time.milliseconds;
      frameRecords.push_back({{"scene_frame", record.sceneFrame},
                              {"orbit_degrees", record.orbitDegrees},
                              {"frame_ms", result.frameMilliseconds[i]},
                              {"lighting_ms", result.lightingMilliseconds[i]},
                              {"gather_ms", result.gatherMilliseconds[i]},
                              {"pass_ms", recordPasses},
                              {"statistics", statisticsJson(record.statistics, result.settings)}});
    }
    modes[renderModeName(result.mode)] = {
        {"frame_ms_median", frame.median},
        {"lighting_ms_median", lighting.median},
        {"gather_ms_median", gather.median},
        {"pass_ms_median", passMedians},
        {"frame_ms", spreadJson(frame, result.frameMilliseconds)},
        {"lighting_ms", spreadJson(lighting, result.lightingMilliseconds)},
        {"gather_ms", spreadJson(gather, result.gatherMilliseconds)},
        {"passes", passes},
        {"level_ms", levels},
        {"statistics", statisticsJson(result.statistics, result.settings)},
        {"frame_records", frameRecords},
    };
  }
  const MultiresolutionSettings& multiresolution = options.gpu.multiresolution;
  nlohmann::json json = {
      {"schema", "penumbra-bench-2"},
      {"date", utcDate()},
      {"machine", {{"cpu", cpuModel()}, {"cores", std::thread::hardware_concurrency()}}},
      {"gl",
       {{"vendor", environment.gl.vendor},
        {"renderer", environment.gl.renderer},
        {"version", environment.gl.version},
        {"platform", environment.gl.platform}}},
      {"timing_method", timingMethodName(profile.timing)},
      {"device_profile", deviceProfileJson(profile)},
      {"scene", environment.scene},
      {"frame", options.frame},
      {"width", environment.size.x},
      {"height", environment.size.y},
      {"lights", environment.lightCount},
      {"vpls_per_light", options.gpu.vplsPerLight},
      {"frames", options.frames},
      {"warmup", options.warmup},
      {"orbit", options.orbit},
      {"settings",
       {{"coarsest_size", multiresolution.coarsestSize},
        {"depth_threshold", shortestDecimal(multiresolution.depthThreshold)},
        {"normal_threshold", shortestDecimal(multiresolution.normalThreshold)},
        {"plane_tolerance", shortestDecimal(multiresolution.planeTolerance)},
        {"light_proximity_threshold", shortestDecimal(multiresolution.lightProximityThreshold)},
        {"shadows", !options.noShadows},
        {"voxel_resolution", options.gpu.shadows.voxels.resolution},
        {"indirect", options.gpu.indirect.enabled}}},
      {"modes", modes},
      {"comparison", nullptr},
  };
  if (comparison) {
    const ImageMetrics& metrics = comparison->metrics;
    json["comparison"] = {
        {"gather_speedup", comparison->gatherSpeedup},
        {"lighting_speedup", comparison->lightingSpeedup},
        {"ideal_speedup", comparison->idealSpeedup},
        {"gather_fraction_of_ideal", comparison->idealSpeedup > 0.0
                                         ? comparison->gatherSpeedup / comparison->idealSpeedup
                                         : 0.0},
        {"lighting_fraction_of_ideal", comparison->idealSpeedup > 0.0
                                           ? comparison->lightingSpeedup / comparison->idealSpeedup
                                           : 0.0},
        {"relative_mse", metrics.relativeMse},
        {"rmse", metrics.rmse},
        {"psnr_db", metrics.psnr},
        {"max_error", metrics.maxError},
    };
  }
  return json;
}

// One table cell: "median [min, max] iqr", or blank when the mode has no such pass.
std::string cell(const std::optional<Spread>& spread) {
  char text[96] = "";
  if (spread) {
    std::snprintf(text, sizeof text, "%10.2f [%9.2f, %9.2f] %8.2f", spread->median, spread->min,
                  spread->max, spread->interquartileRange());
  }
  return text;
}

void printSummary(const BenchOptions& options, const Environment& environment,
                  const DeviceProfile& profile, const std::vector<ModeResult>& results,
                  const std::optional<Comparison>& comparison) {
  std::printf("scene %s, %dx%d, %d VPLs per light x %d lights, scene frame %d\n",
              environment.scene.c_str(), environment.size.x, environment.size.y,
              options.gpu.vplsPerLight, environment.lightCount, options.frame);
  std::printf("machine: %s, %u cores; GL: %s\n", cpuModel().c_str(),
              std::thread::hardware_concurrency(), environment.gl.renderer.c_str());
  std::printf("device profile: %s\n", describe(profile).c_str());
  std::printf("timing: %s, %d measured frames after %d warm-up frames\n",
              timingMethodName(profile.timing), options.frames, options.warmup);
  if (options.orbit > 0)
    std::printf("camera: along an orbit of %d frames about the target\n", options.orbit);
  std::printf("milliseconds: median [min, max] interquartile range\n\n%-14s", "pass");
  for (const ModeResult& result : results)
    std::printf(" %-44s", renderModeName(result.mode));
  std::printf("\n");
  const auto row = [&](const std::string& name, const auto& spreadOfMode) {
    std::printf("%-14s", name.c_str());
    for (const ModeResult& result : results)
      std::printf(" %-44s", cell(spreadOfMode(result)).c_str());
    std::printf("\n");
  };
  for (const StageKey& pass : mergedPassOrder(results))
    row(stageLabel(pass), [&pass](const ModeResult& result) { return result.passSpread(pass); });
  row("gather, all", [](const ModeResult& result) {
    return std::optional<Spread>(spreadOf(result.gatherMilliseconds));
  });
  std::size_t levelCount = 0;
  for (const ModeResult& result : results)
    levelCount = std::max(levelCount, result.levelMilliseconds.size());
  for (std::size_t level = 0; level < levelCount; ++level) {
    row("level " + std::to_string(level) + ", all", [level](const ModeResult& result) {
      return level < result.levelMilliseconds.size()
                 ? std::optional<Spread>(spreadOf(result.levelMilliseconds[level]))
                 : std::nullopt;
    });
  }
  row("frame", [](const ModeResult& result) {
    return std::optional<Spread>(spreadOf(result.frameMilliseconds));
  });
  row("lighting", [](const ModeResult& result) {
    return std::optional<Spread>(spreadOf(result.lightingMilliseconds));
  });
  std::printf(
      "(gather, all: the gather passes of every level; level L, all: the passes at level L; "
      "lighting: the frame without the passes every mode shares)\n");

  for (const ModeResult& result : results) {
    if (result.mode == RenderMode::Hierarchical) {
      std::printf("\nhierarchical samples:\n");
      printStatistics(result.statistics, stdout);
    }
  }
  if (comparison) {
    std::printf("\nnaive / hierarchical: gather %.2fx, lighting %.2fx; ideal %.2fx",
                comparison->gatherSpeedup, comparison->lightingSpeedup, comparison->idealSpeedup);
    if (comparison->idealSpeedup > 0.0) {
      std::printf(" (gather at %.0f%% of ideal)",
                  100.0 * comparison->gatherSpeedup / comparison->idealSpeedup);
    }
    std::printf("\nhierarchical against naive: relative MSE %.3g, RMSE %.3g, PSNR %.2f dB\n",
                comparison->metrics.relativeMse, comparison->metrics.rmse,
                comparison->metrics.psnr);
  }
}

void checkJsonDirectory(const std::string& json) {
  if (json.empty())
    return;
  const std::filesystem::path path(json);
  const auto directory =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  if (!std::filesystem::is_directory(directory)) {
    throw CommandFailure{
        kExitOutput, "--json " + json + ": directory " + directory.string() + " does not exist"};
  }
}

int runBench(const BenchOptions& options) {
  try {
    const std::vector<RenderMode> modes = parseModes(options.modes);
    RenderSettings checked = options.gpu;
    checked.shadows.enabled = !options.noShadows;
    validate(checked);
    checkJsonDirectory(options.json);

    Scene scene = loadScene(parseSceneFile(options.scene));
    for (const std::string& warning : scene.warnings)
      std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    Environment environment;
    environment.scene = options.scene;
    environment.size = options.size.empty() ? scene.camera.size : *parseImageSize(options.size);
    environment.lightCount = static_cast<int>(scene.lights.size());

    gl::HeadlessContext context;
    environment.gl = context.info();
    const DeviceProfile profile = deviceProfileFor(environment.gl);
    std::optional<Renderer> renderer;
    renderer.emplace(scene, environment.size, profile);
    std::vector<ModeResult> results;
    for (const RenderMode mode : modes)
      results.push_back(runMode(*renderer, scene.camera, mode, options));
    const std::optional<Comparison> comparison = compareModes(results);
    throwIfGlErrors();

    printSummary(options, environment, profile, results, comparison);
    if (!options.json.empty()) {
      writeTextFile(options.json,
                    benchJson(options, environment, profile, results, comparison).dump(2) + "\n");
    }
    return kExitOk;
  } catch (...) {
    return reportFailure();
  }
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* bench = app.add_subcommand(
      "bench", "Time each pass of the GPU modes and compare naive with hierarchical");
  bench->add_option("scene", options->scene, "Scene file (default: the built-in demo)");
  bench->add_option("--size", options->size, "Image size WIDTHxHEIGHT (default: the camera's)")
      ->check(imageSizeValidator());
  bench
      ->add_option("--frame", options->frame,
                   "Scene frame rendered every time (time = frame / 30 s)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  bench->add_option("--frames", options->frames, "Measured frames per mode")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  bench->add_option("--warmup", options->warmup, "Unmeasured frames per mode before them")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  bench
      ->add_option("--orbit", options->orbit,
                   "Measure along an orbit of the camera about its target, one turn in this many "
                   "frames; the scene's time advances a frame per measured frame")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  bench->add_option("--modes", options->modes, "Modes to run, in order: hierarchical,naive")
      ->delimiter(',')
      ->capture_default_str();
  addRenderSettingsOptions(*bench, options->gpu);
  bench->add_flag("--no-shadows", options->noShadows, "Every VPL is visible (no voxel pass)");
  bench->add_option("--json", options->json, "Write the results as JSON (docs/bench.md)");
  bench->final_callback([options, &exitCode] { exitCode = runBench(*options); });
}

}  // namespace penumbra::app
