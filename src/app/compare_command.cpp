// `penumbra compare`: image difference metrics with a tolerance and an exit code, like an image
// diff tool, plus an optional false-colour error image and a JSON report.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "app/choice_option.h"
#include "app/command_failure.h"
#include "app/commands.h"
#include "image/image.h"
#include "image/metrics.h"
#include "reference/emitter_mask.h"
#include "scene/scene.h"

namespace penumbra::app {
namespace {

enum class Metric { Rmse, RelativeMse, Psnr, Mae, Max, Ssim, Flip };

struct CompareOptions {
  std::string image;
  std::string reference;
  std::string maskScene;
  int frame = 0;
  Metric metric = Metric::Rmse;
  std::optional<double> tolerance;
  std::string errorImage;
  std::string json;
};

const char* metricName(Metric metric) {
  switch (metric) {
    case Metric::Rmse:
      return "rmse";
    case Metric::RelativeMse:
      return "relmse";
    case Metric::Psnr:
      return "psnr";
    case Metric::Mae:
      return "mae";
    case Metric::Max:
      return "max";
    case Metric::Ssim:
      return "ssim";
    case Metric::Flip:
      return "flip";
  }
  return "";
}

// SSIM and FLIP look at neighbourhoods of the tone-mapped image, so they are computed on demand
// rather than with the per-pixel metrics.
bool isPerceptual(Metric metric) {
  return metric == Metric::Ssim || metric == Metric::Flip;
}

PerceptualMetric perceptualMetric(Metric metric, const Image& image, const Image& reference,
                                  const std::vector<bool>* include) {
  return metric == Metric::Ssim ? structuralSimilarity(image, reference, include)
                                : flip(image, reference, include);
}

// The metrics of one set of pixels: the per-pixel ones, and the chosen perceptual one if any.
struct PixelSetMetrics {
  ImageMetrics metrics;
  std::optional<PerceptualMetric> perceptual;
};

PixelSetMetrics measure(Metric metric, const Image& image, const Image& reference,
                        const std::vector<bool>* include) {
  PixelSetMetrics result{compareImages(image, reference, include), std::nullopt};
  if (isPerceptual(metric)) {
    result.perceptual = perceptualMetric(metric, image, reference, include);
  }
  return result;
}

double metricValue(const PixelSetMetrics& measured, Metric metric) {
  if (measured.perceptual) {
    return measured.perceptual->mean;
  }
  const ImageMetrics& metrics = measured.metrics;
  switch (metric) {
    case Metric::Rmse:
      return metrics.rmse;
    case Metric::RelativeMse:
      return metrics.relativeMse;
    case Metric::Psnr:
      return metrics.psnr;
    case Metric::Mae:
      return metrics.mae;
    case Metric::Max:
      return metrics.maxError;
    case Metric::Ssim:
    case Metric::Flip:
      break;
  }
  return 0.0;
}

bool higherIsBetter(Metric metric) {
  return metric == Metric::Psnr || metric == Metric::Ssim;
}

// Written so that NaN always fails.
bool withinTolerance(double value, Metric metric, double tolerance) {
  return higherIsBetter(metric) ? value >= tolerance : value <= tolerance;
}

void printMetrics(const char* title, const PixelSetMetrics& measured, Metric metric) {
  const ImageMetrics& metrics = measured.metrics;
  std::printf("%-19s %9zu px  rmse %-11.6g relmse %-11.6g psnr %-8.4g dB  mae %-11.6g max %.6g",
              title, metrics.pixelCount, metrics.rmse, metrics.relativeMse, metrics.psnr,
              metrics.mae, metrics.maxError);
  if (measured.perceptual) {
    std::printf("  %s %.6g", metricName(metric), measured.perceptual->mean);
  }
  std::printf("\n");
}

// A perceptually ordered colour map (dark blue through green to yellow), sampled from viridis at
// five points and interpolated linearly: enough for a reader to rank errors by colour.
glm::vec3 errorColour(double fraction) {
  static constexpr std::array<glm::vec3, 5> kControlPoints{{
      {68.0f, 1.0f, 84.0f},
      {59.0f, 82.0f, 139.0f},
      {33.0f, 145.0f, 140.0f},
      {94.0f, 201.0f, 98.0f},
      {253.0f, 231.0f, 37.0f},
  }};
  const double position = std::clamp(fraction, 0.0, 1.0) * (kControlPoints.size() - 1);
  const auto lower = std::min(static_cast<std::size_t>(position), kControlPoints.size() - 2);
  const auto weight = static_cast<float>(position - static_cast<double>(lower));
  return glm::mix(kControlPoints[lower], kControlPoints[lower + 1], weight);
}

// What the error image shows per pixel, from 0 (no error) up, and the scale's top.
struct ErrorMap {
  std::vector<float> errors;
  std::string quantity;  // for the messages: what a pixel's value is
  double scaleMax = 1.0;
};

// Mean |a-b| over RGB, scaled to the largest error that counts, so that emitters left out do not
// wash the map out.
ErrorMap absoluteErrorMap(const Image& image, const Image& reference, const ImageMetrics& checked) {
  ErrorMap map{{}, "mean |a-b| over RGB", 1.0};
  for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
    const glm::vec3 difference = glm::abs(glm::vec3(image.pixels[i] - reference.pixels[i]));
    map.errors.push_back((difference.r + difference.g + difference.b) / 3.0f);
  }
  if (checked.maxError > 0.0 && std::isfinite(checked.maxError)) {
    map.scaleMax = checked.maxError;
  }
  return map;
}

// FLIP is an error in [0,1] already and shows on that fixed scale, so that maps of different
// images can be set side by side; SSIM as its dissimilarity 1 - SSIM, scaled to the largest that
// counts, like the absolute error.
ErrorMap perceptualErrorMap(Metric metric, const PerceptualMetric& perceptual,
                            const std::vector<bool>* include) {
  if (metric == Metric::Flip) {
    return {perceptual.map, "FLIP", 1.0};
  }
  ErrorMap map{{}, "1 - SSIM", 0.0};
  for (std::size_t i = 0; i < perceptual.map.size(); ++i) {
    map.errors.push_back(1.0f - perceptual.map[i]);
    if (include == nullptr || (*include)[i]) {
      map.scaleMax = std::max(map.scaleMax, static_cast<double>(map.errors.back()));
    }
  }
  if (!(map.scaleMax > 0.0)) {
    map.scaleMax = 1.0;
  }
  return map;
}

// The error image: each pixel's error through the colour map from 0 (left end of the legend) to
// the map's scaleMax (right end), masked-out pixels grey, then a black line and a legend strip
// with white ticks at every quarter. The scale goes into the file's ImageDescription.
void writeErrorImage(const ErrorMap& map, int width, int height, const std::vector<bool>* include,
                     const std::filesystem::path& file) {
  const int legendHeight = std::max(6, height / 12);
  const int separatorRow = height;
  const int totalHeight = height + 1 + legendHeight;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * totalHeight * 3, 0);
  const auto put = [&](int x, int y, glm::vec3 colour) {
    const std::size_t at = (static_cast<std::size_t>(y) * width + x) * 3;
    for (int channel = 0; channel < 3; ++channel) {
      rgb[at + channel] = static_cast<std::uint8_t>(std::lround(colour[channel]));
    }
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      if (include != nullptr && !(*include)[i]) {
        put(x, y, glm::vec3(128.0f));
        continue;
      }
      const double error = map.errors[i];
      // A NaN error shows as the top of the scale rather than as the bottom.
      put(x, y, errorColour(std::isnan(error) ? 1.0 : error / map.scaleMax));
    }
  }
  const int tickHeight = std::max(2, legendHeight / 3);
  for (int x = 0; x < width; ++x) {
    put(x, separatorRow, glm::vec3(0.0f));
    const double fraction = width > 1 ? static_cast<double>(x) / (width - 1) : 0.0;
    const double quarters = fraction * 4.0;
    const double pixelsFromTick = std::abs(quarters - std::round(quarters)) * (width - 1) / 4.0;
    const bool tick = pixelsFromTick <= 0.5;
    for (int row = 0; row < legendHeight; ++row) {
      const bool tickPixel = tick && row < tickHeight;
      put(x, separatorRow + 1 + row, tickPixel ? glm::vec3(255.0f) : errorColour(fraction));
    }
  }

  char description[200];
  std::snprintf(description, sizeof description,
                "penumbra compare: %s, colour scale 0 (left of legend) to %.6g "
                "(right), ticks every quarter; grey: masked out",
                map.quantity.c_str(), map.scaleMax);
  OIIO::ImageSpec spec(width, totalHeight, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("ImageDescription", description);
  // Written beside the target and renamed, so a failure never leaves a half-written image.
  const std::filesystem::path temporary =
      file.parent_path() / ("." + file.filename().string() + ".partial");
  auto output = OIIO::ImageOutput::create(file.string());
  if (!output) {
    throw CommandFailure{kExitOutput,
                         "cannot write error image " + file.string() + ": " + OIIO::geterror()};
  }
  if (!output->open(temporary.string(), spec) ||
      !output->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !output->close()) {
    const std::string problem = output->geterror();
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw CommandFailure{kExitOutput, "cannot write error image " + file.string() + ": " + problem};
  }
  std::error_code renameError;
  std::filesystem::rename(temporary, file, renameError);
  if (renameError) {
    std::filesystem::remove(temporary, renameError);
    throw CommandFailure{kExitOutput, "cannot write error image " + file.string()};
  }
}

// JSON has no infinity or NaN: those are written as null.
std::string jsonNumber(double value) {
  if (!std::isfinite(value)) {
    return "null";
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string jsonString(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

std::string jsonMetrics(const PixelSetMetrics& measured, Metric metric) {
  const ImageMetrics& metrics = measured.metrics;
  std::string perceptual;
  if (measured.perceptual) {
    perceptual =
        std::string(", \"") + metricName(metric) + "\": " + jsonNumber(measured.perceptual->mean);
  }
  return "{\"pixels\": " + std::to_string(metrics.pixelCount) +
         ", \"rmse\": " + jsonNumber(metrics.rmse) +
         ", \"relmse\": " + jsonNumber(metrics.relativeMse) +
         ", \"psnr\": " + jsonNumber(metrics.psnr) + ", \"mae\": " + jsonNumber(metrics.mae) +
         ", \"max\": " + jsonNumber(metrics.maxError) + perceptual + "}";
}

void writeJson(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path temporary =
      file.parent_path() / ("." + file.filename().string() + ".partial");
  {
    std::ofstream stream(temporary);
    stream << text;
    if (!stream.flush()) {
      throw CommandFailure{kExitOutput, "cannot write " + file.string()};
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw CommandFailure{kExitOutput, "cannot write " + file.string()};
  }
}

std::vector<bool> nonEmitterPixels(const CompareOptions& options, glm::ivec2 size) {
  Scene scene;
  try {
    scene = loadScene(parseSceneFile(options.maskScene));
  } catch (const std::exception& error) {
    throw CommandFailure{kExitBadInput, std::string("--mask-emitters: ") + error.what()};
  }
  for (const std::string& warning : scene.warnings) {
    std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
  }
  std::vector<bool> include = emitterMask(scene, size, options.frame);
  include.flip();
  return include;
}

int runCompare(const CompareOptions& options) {
  try {
    Image image;
    Image reference;
    try {
      image = loadImage(options.image);
      reference = loadImage(options.reference);
    } catch (const ImageError& error) {
      throw CommandFailure{kExitBadInput, error.what()};
    }
    if (image.width != reference.width || image.height != reference.height) {
      throw CommandFailure{kExitBadInput, "images differ in size: " + std::to_string(image.width) +
                                              "x" + std::to_string(image.height) + " vs " +
                                              std::to_string(reference.width) + "x" +
                                              std::to_string(reference.height)};
    }
    const Metric metric = options.metric;
    const PixelSetMetrics all = measure(metric, image, reference, nullptr);
    std::optional<std::vector<bool>> include;
    std::optional<PixelSetMetrics> masked;
    if (!options.maskScene.empty()) {
      include = nonEmitterPixels(options, {reference.width, reference.height});
      masked = measure(metric, image, reference, &*include);
    }
    // The tolerance applies to the pixels that count: the non-emitter ones when masking.
    const PixelSetMetrics& checked = masked ? *masked : all;

    std::printf("compare %s against reference %s (%dx%d)\n", options.image.c_str(),
                options.reference.c_str(), reference.width, reference.height);
    printMetrics("all pixels", all, metric);
    if (masked) {
      printMetrics("non-emitter pixels", *masked, metric);
    }

    int exitCode = kExitOk;
    if (options.tolerance) {
      const double value = metricValue(checked, metric);
      const bool pass = withinTolerance(value, metric, *options.tolerance);
      exitCode = pass ? kExitOk : kExitFailure;
      const char* relation = higherIsBetter(metric) ? (pass ? ">=" : "<") : (pass ? "<=" : ">");
      std::printf("%s %.6g %s tolerance %.6g: %s\n", metricName(metric), value, relation,
                  *options.tolerance, pass ? "pass" : "FAIL");
    }

    if (!options.errorImage.empty()) {
      const std::vector<bool>* counted = include ? &*include : nullptr;
      const ErrorMap map = checked.perceptual
                               ? perceptualErrorMap(metric, *checked.perceptual, counted)
                               : absoluteErrorMap(image, reference, checked.metrics);
      writeErrorImage(map, reference.width, reference.height, counted, options.errorImage);
      std::printf("error image %s: %s, colour scale 0 (legend left) to %.6g (legend right)\n",
                  options.errorImage.c_str(), map.quantity.c_str(), map.scaleMax);
    }

    if (!options.json.empty()) {
      std::string text = "{\n  \"image\": " + jsonString(options.image) +
                         ",\n  \"reference\": " + jsonString(options.reference) +
                         ",\n  \"width\": " + std::to_string(reference.width) +
                         ",\n  \"height\": " + std::to_string(reference.height) +
                         ",\n  \"all\": " + jsonMetrics(all, metric);
      if (masked) {
        text += ",\n  \"nonEmitter\": " + jsonMetrics(*masked, metric);
      }
      if (options.tolerance) {
        text += ",\n  \"metric\": " + jsonString(metricName(metric)) +
                ",\n  \"tolerance\": " + jsonNumber(*options.tolerance) +
                ",\n  \"pass\": " + (exitCode == kExitOk ? "true" : "false");
      }
      writeJson(options.json, text + "\n}\n");
    }
    std::fflush(stdout);
    return exitCode;
  } catch (...) {
    return reportFailure();
  }
}

}  // namespace

void addCompareCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* compare = app.add_subcommand(
      "compare",
      "Compare an image with a reference: RMSE, relative MSE, PSNR, MAE and max error over RGB, "
      "and SSIM or FLIP of the tone-mapped images when --metric names them. With --tol, exits 1 "
      "when the --metric is out of tolerance");
  compare->add_option("image", options->image, "Image to check")->required();
  compare->add_option("reference", options->reference, "Reference image (b in the metrics)")
      ->required();
  compare->add_option("--mask-emitters", options->maskScene,
                      "Scene file: leave out pixels whose camera ray (the scene's camera at the "
                      "image size) first hits a light quad; the tolerance then applies to the "
                      "other pixels");
  compare->add_option("--frame", options->frame, "Frame of the scene for --mask-emitters")
      ->check(CLI::NonNegativeNumber);
  ChoiceNames<Metric> metrics;
  for (const Metric metric : {Metric::Rmse, Metric::RelativeMse, Metric::Psnr, Metric::Mae,
                              Metric::Max, Metric::Ssim, Metric::Flip})
    metrics.emplace_back(metricName(metric), metric);
  addChoiceOption(*compare, "--metric", options->metric, metrics,
                  "Metric --tol and --error-image apply to (ssim, flip: on the image tone-mapped "
                  "as render's PNG output, docs/metrics.md)");
  compare->add_option(
      "--tol", options->tolerance,
      "Tolerance: fail (exit 1) when the metric is above it (psnr, ssim: below it)");
  compare->add_option("--error-image", options->errorImage,
                      "Write a false-colour map with a legend strip (PNG): mean |a-b|, or per "
                      "pixel 1 - SSIM or FLIP with --metric ssim or flip");
  compare->add_option("--json", options->json, "Write the metrics as JSON");
  compare->final_callback([options, &exitCode] { exitCode = runCompare(*options); });
}

}  // namespace penumbra::app
