#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

std::string sizeText(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

}  // namespace

ImageMetrics compareImages(const Image& a, const Image& b, const std::vector<bool>* includePixel) {
  if (a.width != b.width || a.height != b.height) {
    throw ImageError("images differ in size: " + sizeText(a) + " vs " + sizeText(b));
  }
  if (includePixel != nullptr && includePixel->size() != b.pixels.size()) {
    throw ImageError("mask has " + std::to_string(includePixel->size()) + " entries for a " +
                     sizeText(b) + " image");
  }
  // Sums in double: a 4k image has 25 million terms.
  double squaredSum = 0.0;
  double relativeSquaredSum = 0.0;
  double absoluteSum = 0.0;
  double maxError = 0.0;
  double peak = 0.0;
  // std::max drops a NaN, which must show in the result instead (the sums keep it already).
  bool sawNan = false;
  std::size_t pixelCount = 0;
  for (std::size_t i = 0; i < b.pixels.size(); ++i) {
    if (includePixel != nullptr && !(*includePixel)[i]) {
      continue;
    }
    ++pixelCount;
    for (int channel = 0; channel < 3; ++channel) {
      const double reference = b.pixels[i][channel];
      const double error = static_cast<double>(a.pixels[i][channel]) - reference;
      squaredSum += error * error;
      relativeSquaredSum += error * error / (reference * reference + 0.01);
      absoluteSum += std::abs(error);
      maxError = std::max(maxError, std::abs(error));
      sawNan = sawNan || std::isnan(error);
      peak = std::max(peak, reference);
    }
  }

  ImageMetrics metrics;
  metrics.pixelCount = pixelCount;
  if (pixelCount == 0) {
    metrics.psnr = std::numeric_limits<double>::infinity();
    return metrics;
  }
  const double valueCount = 3.0 * static_cast<double>(pixelCount);
  const double mse = squaredSum / valueCount;
  metrics.rmse = std::sqrt(mse);
  metrics.relativeMse = relativeSquaredSum / valueCount;
  metrics.mae = absoluteSum / valueCount;
  metrics.maxError = sawNan ? std::numeric_limits<double>::quiet_NaN() : maxError;
  if (peak <= 0.0) {
    peak = 1.0;
  }
  metrics.psnr =
      mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(peak * peak / mse);
  return metrics;
}

}  // namespace penumbra
