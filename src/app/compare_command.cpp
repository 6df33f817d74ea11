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

enum class Metric { Rmse, RelativeMse, Psnr, Mae, Max };

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
  }
  return "";
}

double metricValue(const ImageMetrics& metrics, Metric metric) {
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
  }
  return 0.0;
}

// PSNR is better when higher, the others when lower. Written so that NaN always fails.
bool withinTolerance(double value, Metric metric, double tolerance) {
  return metric == Metric::Psnr ? value >= tolerance : value <= tolerance;
}

void printMetrics(const char* title, const ImageMetrics& metrics) {
  std::printf("%-19s %9zu px  rmse %-11.6g relmse %-11.6g psnr %-8.4g dB  mae %-11.6g max %.6g\n",
              title, metrics.pixelCount, metrics.rmse, metrics.relativeMse, metrics.psnr,
              metrics.mae, metrics.maxError);
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

// The error image: per pixel mean |a-b| over RGB through the colour map from 0 (left end of the
// legend) to `scaleMax` (right end), masked-out pixels grey, then a black line and a legend strip
// with white ticks at every quarter. The scale goes into the file's ImageDescription.
void writeErrorImage(const Image& image, const Image& reference, const std::vector<bool>* include,
                     double scaleMax, const std::filesystem::path& file) {
  const int width = image.width;
  const int legendHeight = std::max(6, image.height / 12);
  const int separatorRow = image.height;
  const int totalHeight = image.height + 1 + legendHeight;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * totalHeight * 3, 0);
  const auto put = [&](int x, int y, glm::vec3 colour) {
    const std::size_t at = (static_cast<std::size_t>(y) * width + x) * 3;
    for (int channel = 0; channel < 3; ++channel) {
      rgb[at + channel] = static_cast<std::uint8_t>(std::lround(colour[channel]));
    }
  };
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      if (include != nullptr && !(*include)[i]) {
        put(x, y, glm::vec3(128.0f));
        continue;
      }
      const glm::vec3 difference = glm::abs(glm::vec3(image.pixels[i] - reference.pixels[i]));
      const double error = (difference.r + difference.g + difference.b) / 3.0;
      // A NaN error shows as the top of the scale rather than as the bottom.
      put(x, y, errorColour(std::isnan(error) ? 1.0 : error / scaleMax));
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

  char description[160];
  std::snprintf(description, sizeof description,
                "penumbra compare: mean |a-b| over RGB, colour scale 0 (left of legend) to %.6g "
                "(right), ticks every quarter; grey: masked out",
                scaleMax);
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

std::string jsonMetrics(const ImageMetrics& metrics) {
  return "{\"pixels\": " + std::to_string(metrics.pixelCount) +
         ", \"rmse\": " + jsonNumber(metrics.rmse) +
         ", \"relmse\": " + jsonNumber(metrics.relativeMse) +
         ", \"psnr\": " + jsonNumber(metrics.psnr) + ", \"mae\": " + jsonNumber(metrics.mae) +
         ", \"max\": " + jsonNumber(metrics.maxError) + "}";
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
    const ImageMetrics all = compareImages(image, reference);
    std::optional<std::vector<bool>> include;
    std::optional<ImageMetrics> masked;
    if (!options.maskScene.empty()) {
      include = nonEmitterPixels(options, {reference.width, reference.height});
      masked = compareImages(image, reference, &*include);
    }
    // The tolerance applies to the pixels that count: the non-emitter ones when masking.
    const ImageMetrics& checked = masked ? *masked : all;

    std::printf("compare %s against reference %s (%dx%d)\n", options.image.c_str(),
                options.reference.c_str(), reference.width, reference.height);
    printMetrics("all pixels", all);
    if (masked) {
      printMetrics("non-emitter pixels", *masked);
    }

    const Metric metric = options.metric;
    int exitCode = kExitOk;
    if (options.tolerance) {
      const double value = metricValue(checked, metric);
      const bool pass = withinTolerance(value, metric, *options.tolerance);
      exitCode = pass ? kExitOk : kExitFailure;
      const char* relation = metric == Metric::Psnr ? (pass ? ">=" : "<") : (pass ? "<=" : ">");
      std::printf("%s %.6g %s tolerance %.6g: %s\n", metricName(metric), value, relation,
                  *options.tolerance, pass ? "pass" : "FAIL");
    }

    if (!options.errorImage.empty()) {
      // Scaled to the largest error that counts, so emitters left out do not wash the map out.
      const double scaleMax =
          checked.maxError > 0.0 && std::isfinite(checked.maxError) ? checked.maxError : 1.0;
      writeErrorImage(image, reference, include ? &*include : nullptr, scaleMax,
                      options.errorImage);
      std::printf(
          "error image %s: mean |a-b| over RGB, colour scale 0 (legend left) to %.6g "
          "(legend right)\n",
          options.errorImage.c_str(), scaleMax);
    }

    if (!options.json.empty()) {
      std::string text = "{\n  \"image\": " + jsonString(options.image) +
                         ",\n  \"reference\": " + jsonString(options.reference) +
                         ",\n  \"width\": " + std::to_string(reference.width) +
                         ",\n  \"height\": " + std::to_string(reference.height) +
                         ",\n  \"all\": " + jsonMetrics(all);
      if (masked) {
        text += ",\n  \"nonEmitter\": " + jsonMetrics(*masked);
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
      "Compare an image with a reference: RMSE, relative MSE, PSNR, MAE and max error over RGB. "
      "With --tol, exits 1 when the --metric is out of tolerance");
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
  for (const Metric metric :
       {Metric::Rmse, Metric::RelativeMse, Metric::Psnr, Metric::Mae, Metric::Max})
    metrics.emplace_back(metricName(metric), metric);
  addChoiceOption(*compare, "--metric", options->metric, metrics, "Metric --tol applies to");
  compare->add_option("--tol", options->tolerance,
                      "Tolerance: fail (exit 1) when the metric is above it (psnr: below it)");
  compare->add_option("--error-image", options->errorImage,
                      "Write a false-colour map of mean |a-b| with a legend strip (PNG)");
  compare->add_option("--json", options->json, "Write the metrics as JSON");
  compare->final_callback([options, &exitCode] { exitCode = runCompare(*options); });
}

}  // namespace penumbra::app
