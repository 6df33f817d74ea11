#include "image/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

namespace penumbra {
namespace {

std::string sizeText(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

void checkComparable(const Image& a, const Image& b, const std::vector<bool>* includePixel) {
  if (a.width != b.width || a.height != b.height) {
    throw ImageError("images differ in size: " + sizeText(a) + " vs " + sizeText(b));
  }
  if (includePixel != nullptr && includePixel->size() != b.pixels.size()) {
    throw ImageError("mask has " + std::to_string(includePixel->size()) + " entries for a " +
                     sizeText(b) + " image");
  }
}

bool included(const std::vector<bool>* includePixel, std::size_t i) {
  return includePixel == nullptr || (*includePixel)[i];
}

// One channel of an image, in double so that sums of many small terms keep their precision.
struct Plane {
  int width = 0;
  int height = 0;
  std::vector<double> values;

  Plane(int planeWidth, int planeHeight)
      : width(planeWidth),
        height(planeHeight),
        values(static_cast<std::size_t>(planeWidth) * static_cast<std::size_t>(planeHeight), 0.0) {}
  double& operator[](std::size_t i) { return values[i]; }
  double operator[](std::size_t i) const { return values[i]; }
};

// Outside the image: zero (windows cut off at the border, renormalised by the caller) or the
// nearest edge pixel repeated.
enum class Border { Zero, Repeat };

// A 1D kernel of odd length centred on its middle tap.
using Kernel = std::vector<double>;

// out(x) = sum_j kernel[j] in(x + j - r), r the kernel's radius, along the rows or the columns.
Plane correlateAxis(const Plane& in, const Kernel& kernel, bool alongRows, Border border) {
  Plane out(in.width, in.height);
  const int radius = static_cast<int>(kernel.size() / 2);
  const int length = alongRows ? in.width : in.height;
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      const int position = alongRows ? x : y;
      double sum = 0.0;
      for (int j = 0; j < static_cast<int>(kernel.size()); ++j) {
        int at = position + j - radius;
        if (at < 0 || at >= length) {
          if (border == Border::Zero) {
            continue;
          }
          at = std::clamp(at, 0, length - 1);
        }
        const std::size_t source = alongRows ? static_cast<std::size_t>(y) * in.width + at
                                             : static_cast<std::size_t>(at) * in.width + x;
        sum += kernel[static_cast<std::size_t>(j)] * in[source];
      }
      out[static_cast<std::size_t>(y) * in.width + x] = sum;
    }
  }
  return out;
}

// The 2D kernel horizontal(x) * vertical(y).
Plane correlate(const Plane& in, const Kernel& horizontal, const Kernel& vertical, Border border) {
  return correlateAxis(correlateAxis(in, horizontal, true, border), vertical, false, border);
}

Kernel sampledKernel(int radius, const auto& function) {
  Kernel kernel;
  for (int x = -radius; x <= radius; ++x) {
    kernel.push_back(function(static_cast<double>(x)));
  }
  return kernel;
}

Kernel normalised(Kernel kernel, double sum) {
  for (double& tap : kernel) {
    tap /= sum;
  }
  return kernel;
}

double kernelSum(const Kernel& kernel) {
  double sum = 0.0;
  for (const double tap : kernel) {
    sum += tap;
  }
  return sum;
}

Kernel gaussianKernel(int radius, double sigma) {
  const Kernel kernel =
      sampledKernel(radius, [sigma](double x) { return std::exp(-x * x / (2.0 * sigma * sigma)); });
  return normalised(kernel, kernelSum(kernel));
}

// What a person sees of a linear value on a monitor: `render`'s PNG tone map at exposure 0, in
// [0,1]. NaN stays NaN, so that it shows in the metric.
double toneMapped(float linear) {
  return std::isnan(linear) ? linear : linearToSrgb(std::clamp(linear, 0.0f, 1.0f));
}

double meanOver(const std::vector<float>& map, const std::vector<bool>* includePixel,
                std::size_t& pixelCount) {
  double sum = 0.0;
  pixelCount = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (included(includePixel, i)) {
      sum += map[i];
      ++pixelCount;
    }
  }
  return pixelCount == 0 ? 0.0 : sum / static_cast<double>(pixelCount);
}

// --- FLIP --------------------------------------------------------------------------------------

using Vec3d = std::array<double, 3>;

// Linear sRGB (D65) to CIE XYZ and back.
Vec3d linearRgbToXyz(const Vec3d& rgb) {
  return {0.4124564 * rgb[0] + 0.3575761 * rgb[1] + 0.1804375 * rgb[2],
          0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2],
          0.0193339 * rgb[0] + 0.1191920 * rgb[1] + 0.9503041 * rgb[2]};
}

Vec3d xyzToLinearRgb(const Vec3d& xyz) {
  return {3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2],
          -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2],
          0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2]};
}

// The reference white: the XYZ of RGB (1,1,1).
const Vec3d& whitePoint() {
  static const Vec3d white = linearRgbToXyz({1.0, 1.0, 1.0});
  return white;
}

// YCxCz, the linearised CIELAB opponent space the CSFs are defined in: Y achromatic, Cx red-green,
// Cz blue-yellow.
Vec3d xyzToYcxcz(const Vec3d& xyz) {
  const Vec3d& white = whitePoint();
  const double x = xyz[0] / white[0];
  const double y = xyz[1] / white[1];
  const double z = xyz[2] / white[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3d ycxczToXyz(const Vec3d& ycxcz) {
  const Vec3d& white = whitePoint();
  const double y = (ycxcz[0] + 16.0) / 116.0;
  return {(ycxcz[1] / 500.0 + y) * white[0], y * white[1], (y - ycxcz[2] / 200.0) * white[2]};
}

// CIELAB with the Hunt effect: chroma scales with lightness (a and b times L/100).
Vec3d huntAdjustedLab(const Vec3d& linearRgb) {
  const Vec3d xyz = linearRgbToXyz(linearRgb);
  const Vec3d& white = whitePoint();
  constexpr double kDelta = 6.0 / 29.0;
  const auto f = [](double t) {
    return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
  };
  const double fx = f(xyz[0] / white[0]);
  const double fy = f(xyz[1] / white[1]);
  const double fz = f(xyz[2] / white[2]);
  const double lightness = 116.0 * fy - 16.0;
  return {lightness, 0.01 * lightness * 500.0 * (fx - fy), 0.01 * lightness * 200.0 * (fy - fz)};
}

// HyAB: the lightness difference taken apart from the chroma difference, better for large colour
// differences than the Euclidean distance.
double hyab(const Vec3d& p, const Vec3d& q) {
  return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// The contrast sensitivity of one opponent channel as a spatial filter: the inverse 2D Fourier
// transform of a1 exp(-b1 f^2) + a2 exp(-b2 f^2) (f in cycles per degree) is
// sum_k a_k pi/b_k exp(-pi^2 r^2 / b_k), r in degrees; a sum of separable Gaussians.
struct ContrastSensitivity {
  double a1, b1, a2, b2;
};

// The paper's parameters for the achromatic, red-green and blue-yellow channels.
constexpr std::array<ContrastSensitivity, 3> kContrastSensitivities{{
    {1.0, 0.0047, 0.0, 1e-5},
    {1.0, 0.0053, 0.0, 1e-5},
    {34.1, 0.04, 13.5, 0.025},
}};

Plane filterByContrastSensitivity(const Plane& channel, const ContrastSensitivity& csf,
                                  double pixelsPerDegree) {
  // Three standard deviations of the widest Gaussian of all channels, as the paper sizes it.
  double widest = 0.0;
  for (const ContrastSensitivity& each : kContrastSensitivities) {
    widest = std::max({widest, each.b1, each.b2});
  }
  const int radius = static_cast<int>(std::ceil(
      3.0 * std::sqrt(widest / (2.0 * std::numbers::pi * std::numbers::pi)) * pixelsPerDegree));
  const auto gaussian = [&](double b) {
    return sampledKernel(radius, [&](double x) {
      const double degrees = x / pixelsPerDegree;
      return std::exp(-std::numbers::pi * std::numbers::pi * degrees * degrees / b);
    });
  };
  // Each Gaussian's share of the filter is its amplitude times its sampled 2D kernel's sum; the
  // filter as a whole sums to 1.
  const Kernel narrow = gaussian(csf.b1);
  const Kernel wide = gaussian(csf.b2);
  const double narrowShare =
      csf.a1 * std::numbers::pi / csf.b1 * kernelSum(narrow) * kernelSum(narrow);
  const double wideShare = csf.a2 * std::numbers::pi / csf.b2 * kernelSum(wide) * kernelSum(wide);
  const Kernel narrowUnit = normalised(narrow, kernelSum(narrow));
  Plane filtered = correlate(channel, narrowUnit, narrowUnit, Border::Repeat);
  if (wideShare > 0.0) {
    const Kernel wideUnit = normalised(wide, kernelSum(wide));
    const Plane wideFiltered = correlate(channel, wideUnit, wideUnit, Border::Repeat);
    for (std::size_t i = 0; i < filtered.values.size(); ++i) {
      filtered[i] =
          (narrowShare * filtered[i] + wideShare * wideFiltered[i]) / (narrowShare + wideShare);
    }
  }
  return filtered;
}

// Per pixel, the linear RGB a person perceives after the eye's contrast sensitivity, clamped to
// the displayable range, as Hunt-adjusted CIELAB.
std::vector<Vec3d> perceivedColours(const std::array<Plane, 3>& ycxcz, double pixelsPerDegree) {
  std::vector<Plane> filtered;
  for (std::size_t channel = 0; channel < 3; ++channel) {
    filtered.push_back(filterByContrastSensitivity(ycxcz[channel], kContrastSensitivities[channel],
                                                   pixelsPerDegree));
  }
  std::vector<Vec3d> colours(ycxcz[0].values.size());
  for (std::size_t i = 0; i < colours.size(); ++i) {
    Vec3d rgb = xyzToLinearRgb(ycxczToXyz({filtered[0][i], filtered[1][i], filtered[2][i]}));
    for (double& value : rgb) {
      value = std::clamp(value, 0.0, 1.0);
    }
    colours[i] = huntAdjustedLab(rgb);
  }
  return colours;
}

// Edge (first derivative of a Gaussian) and point (second derivative) strength of the achromatic
// channel, with the paper's feature width of 0.082 degrees.
struct Features {
  std::vector<double> edge;
  std::vector<double> point;
};

Features detectFeatures(const Plane& achromatic, double pixelsPerDegree) {
  const double sigma = 0.5 * 0.082 * pixelsPerDegree;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  const Kernel gaussian =
      sampledKernel(radius, [sigma](double x) { return std::exp(-x * x / (2.0 * sigma * sigma)); });
  const Kernel firstDerivative = sampledKernel(radius, [sigma](double x) {
    return -x / (sigma * sigma) * std::exp(-x * x / (2.0 * sigma * sigma));
  });
  const Kernel secondDerivative = sampledKernel(radius, [sigma](double x) {
    return (x * x / (sigma * sigma) - 1.0) / (sigma * sigma) *
           std::exp(-x * x / (2.0 * sigma * sigma));
  });
  // Edge kernel d(x) g(y): scaled so that its positive weights sum to 1 and its negative ones to
  // -1 (it is odd, so one scale does both).
  double positiveFirst = 0.0;
  for (const double tap : firstDerivative) {
    positiveFirst += std::max(0.0, tap);
  }
  const Kernel edgeAcross = normalised(firstDerivative, positiveFirst * kernelSum(gaussian));
  // Point kernel s(x) g(y): its 2D mean taken off so that it sums to 0, then scaled like the
  // edge kernel. The mean is a box filter, so the kernel stays a difference of separable ones.
  const std::size_t side = gaussian.size();
  const double mean =
      kernelSum(secondDerivative) * kernelSum(gaussian) / static_cast<double>(side * side);
  double positivePoint = 0.0;
  for (const double across : secondDerivative) {
    for (const double along : gaussian) {
      positivePoint += std::max(0.0, across * along - mean);
    }
  }
  const Kernel pointAcross = normalised(secondDerivative, positivePoint);
  const Kernel box(side, 1.0);
  const Plane boxed = correlate(achromatic, box, box, Border::Repeat);

  Features features;
  const Plane edgeX = correlate(achromatic, edgeAcross, gaussian, Border::Repeat);
  const Plane edgeY = correlate(achromatic, gaussian, edgeAcross, Border::Repeat);
  const Plane pointX = correlate(achromatic, pointAcross, gaussian, Border::Repeat);
  const Plane pointY = correlate(achromatic, gaussian, pointAcross, Border::Repeat);
  for (std::size_t i = 0; i < achromatic.values.size(); ++i) {
    const double boxPart = mean / positivePoint * boxed[i];
    features.edge.push_back(std::hypot(edgeX[i], edgeY[i]));
    features.point.push_back(std::hypot(pointX[i] - boxPart, pointY[i] - boxPart));
  }
  return features;
}

// The YCxCz planes of an image's tone-mapped, displayed (linear, in [0,1]) colours.
std::array<Plane, 3> displayedYcxcz(const Image& image) {
  std::array<Plane, 3> planes{Plane(image.width, image.height), Plane(image.width, image.height),
                              Plane(image.width, image.height)};
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    Vec3d rgb{};
    for (int channel = 0; channel < 3; ++channel) {
      rgb[static_cast<std::size_t>(channel)] =
          srgbToLinear(static_cast<float>(toneMapped(image.pixels[i][channel])));
    }
    const Vec3d ycxcz = xyzToYcxcz(linearRgbToXyz(rgb));
    for (std::size_t channel = 0; channel < 3; ++channel) {
      planes[channel][i] = ycxcz[channel];
    }
  }
  return planes;
}

}  // namespace

double FlipViewing::pixelsPerDegree() const {
  return distanceMetres * (monitorWidthPixels / monitorWidthMetres) * std::numbers::pi / 180.0;
}

PerceptualMetric structuralSimilarity(const Image& a, const Image& b,
                                      const std::vector<bool>* includePixel) {
  checkComparable(a, b, includePixel);
  constexpr double kC1 = 0.01 * 0.01;
  constexpr double kC2 = 0.03 * 0.03;
  const Kernel window = gaussianKernel(5, 1.5);
  const std::size_t count = b.pixels.size();
  std::vector<double> channelMean(count, 0.0);
  Plane weight(b.width, b.height);
  for (std::size_t i = 0; i < count; ++i) {
    weight[i] = included(includePixel, i) ? 1.0 : 0.0;
  }
  const Plane windowWeight = correlate(weight, window, window, Border::Zero);
  for (int channel = 0; channel < 3; ++channel) {
    // The window's weighted sums of a, b, a^2, b^2 and ab, the pixels left out weighing 0.
    std::array<Plane, 5> moments{weight, weight, weight, weight, weight};
    for (std::size_t i = 0; i < count; ++i) {
      const double x = weight[i] > 0.0 ? toneMapped(a.pixels[i][channel]) : 0.0;
      const double y = weight[i] > 0.0 ? toneMapped(b.pixels[i][channel]) : 0.0;
      moments[0][i] = x;
      moments[1][i] = y;
      moments[2][i] = x * x;
      moments[3][i] = y * y;
      moments[4][i] = x * y;
    }
    for (Plane& moment : moments) {
      moment = correlate(moment, window, window, Border::Zero);
    }
    for (std::size_t i = 0; i < count; ++i) {
      if (weight[i] == 0.0) {
        continue;
      }
      const double total = windowWeight[i];
      const double meanA = moments[0][i] / total;
      const double meanB = moments[1][i] / total;
      const double varianceA = moments[2][i] / total - meanA * meanA;
      const double varianceB = moments[3][i] / total - meanB * meanB;
      const double covariance = moments[4][i] / total - meanA * meanB;
      const double similarity =
          (2.0 * meanA * meanB + kC1) * (2.0 * covariance + kC2) /
          ((meanA * meanA + meanB * meanB + kC1) * (varianceA + varianceB + kC2));
      channelMean[i] += similarity / 3.0;
    }
  }
  PerceptualMetric result;
  for (std::size_t i = 0; i < count; ++i) {
    // A pixel left out has nothing to tell apart.
    result.map.push_back(weight[i] > 0.0 ? static_cast<float>(channelMean[i]) : 1.0f);
  }
  result.mean = meanOver(result.map, includePixel, result.pixelCount);
  return result;
}

PerceptualMetric flip(const Image& test, const Image& reference,
                      const std::vector<bool>* includePixel, const FlipViewing& viewing) {
  checkComparable(test, reference, includePixel);
  const double pixelsPerDegree = viewing.pixelsPerDegree();
  Image shown = test;
  for (std::size_t i = 0; i < shown.pixels.size(); ++i) {
    if (!included(includePixel, i)) {
      shown.pixels[i] = reference.pixels[i];
    }
  }
  const std::array<Plane, 3> testYcxcz = displayedYcxcz(shown);
  const std::array<Plane, 3> referenceYcxcz = displayedYcxcz(reference);

  // Colour: the HyAB distance of the perceived colours, raised to q_c = 0.7 and mapped to [0,1]
  // relative to the largest distance of the display (green against blue), compressing the
  // largest 60% of differences into the top 5% of the range (p_c = 0.4, p_t = 0.95).
  constexpr double kColourExponent = 0.7;
  constexpr double kCompressedFrom = 0.4;
  constexpr double kCompressedTo = 0.95;
  const double largest = std::pow(
      hyab(huntAdjustedLab({0.0, 1.0, 0.0}), huntAdjustedLab({0.0, 0.0, 1.0})), kColourExponent);
  const std::vector<Vec3d> testColours = perceivedColours(testYcxcz, pixelsPerDegree);
  const std::vector<Vec3d> referenceColours = perceivedColours(referenceYcxcz, pixelsPerDegree);

  // Features: on the achromatic channel, normalised to [0,1], of the unfiltered images.
  const auto achromatic = [](const Plane& luminance) {
    Plane normalisedLuminance = luminance;
    for (double& value : normalisedLuminance.values) {
      value = (value + 16.0) / 116.0;
    }
    return normalisedLuminance;
  };
  const Features testFeatures = detectFeatures(achromatic(testYcxcz[0]), pixelsPerDegree);
  const Features referenceFeatures = detectFeatures(achromatic(referenceYcxcz[0]), pixelsPerDegree);
  constexpr double kFeatureExponent = 0.5;

  PerceptualMetric result;
  result.map.resize(reference.pixels.size());
  for (std::size_t i = 0; i < result.map.size(); ++i) {
    const double distance = std::pow(hyab(testColours[i], referenceColours[i]), kColourExponent);
    const double colourError = distance < kCompressedFrom * largest
                                   ? kCompressedTo / (kCompressedFrom * largest) * distance
                                   : kCompressedTo + (distance - kCompressedFrom * largest) /
                                                         (largest - kCompressedFrom * largest) *
                                                         (1.0 - kCompressedTo);
    const double featureDifference =
        std::max(std::abs(testFeatures.edge[i] - referenceFeatures.edge[i]),
                 std::abs(testFeatures.point[i] - referenceFeatures.point[i]));
    const double featureError = std::pow(featureDifference / std::numbers::sqrt2, kFeatureExponent);
    // Differences at edges and points are seen more easily: the feature error lifts the colour
    // error towards 1.
    // A NaN input spreads through the filters to NaN here, as it must.
    result.map[i] = static_cast<float>(std::pow(colourError, 1.0 - featureError));
  }
  result.mean = meanOver(result.map, includePixel, result.pixelCount);
  return result;
}

ImageMetrics compareImages(const Image& a, const Image& b, const std::vector<bool>* includePixel) {
  checkComparable(a, b, includePixel);
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
