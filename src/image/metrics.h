#pragma once
// Image difference metrics for `penumbra compare` and for tests.

#include <optional>
#include <string>
#include <vector>

#include "image/image.h"

namespace penumbra {

// All metrics are over the RGB channels of the pixels taken into account.
struct ImageMetrics {
  double rmse = 0.0;         // sqrt(mean (a-b)^2)
  double relativeMse = 0.0;  // mean (a-b)^2 / (b^2 + 0.01), b the second (reference) image
  double psnr = 0.0;         // 10 log10(peak^2 / mse), peak = max of b over RGB (1 if b is black)
  double mae = 0.0;          // mean |a-b|
  double maxError = 0.0;     // max |a-b|
  std::size_t pixelCount = 0;
};

// Throws ImageError when the sizes differ. With a mask, only pixels whose mask entry is true count.
ImageMetrics compareImages(const Image& a, const Image& b,
                           const std::vector<bool>* includePixel = nullptr);

// The two perceptual metrics judge what a person sees: the image as `render` writes it to a PNG at
// the default exposure, each linear RGB value clamped to [0,1] and sRGB encoded (before the 8-bit
// rounding). A per-pixel map and its mean over the pixels taken into account.
struct PerceptualMetric {
  std::vector<float> map;  // per pixel, row 0 at the top; NaN where an input is NaN
  double mean = 0.0;       // over the pixels taken into account
  std::size_t pixelCount = 0;
};

// SSIM (Wang, Bovik, Sheikh and Simoncelli 2004) on each tone-mapped RGB channel, averaged over
// the channels: an 11x11 Gaussian window of sigma 1.5 px, C1 = (0.01)^2, C2 = (0.03)^2. 1 for
// identical images, lower is worse. With a mask, the pixels left out are left out of every window
// as well as of the mean, and windows at the image's border are cut off and renormalised alike.
PerceptualMetric structuralSimilarity(const Image& a, const Image& b,
                                      const std::vector<bool>* includePixel = nullptr);

// The viewing conditions FLIP assumes: a 0.7 m wide monitor of 3840 pixels across, seen from
// 0.7 m: about 67 pixels per degree of visual angle (the paper's defaults).
struct FlipViewing {
  double monitorWidthMetres = 0.7;
  double monitorWidthPixels = 3840.0;
  double distanceMetres = 0.7;
  double pixelsPerDegree() const;
};

// LDR-FLIP (Andersson, Nilsson, Akenine-Moeller, Oskarsson, Astroem and Fairchild 2020, "FLIP: A
// Difference Evaluator for Alternating Images"): the perceived difference when flipping between
// `test` and `reference`, 0 (none) to 1, lower is better. Computed on the whole tone-mapped
// images (edge pixels repeated past the border); with a mask, the pixels left out take the
// reference's value in both images, so that they add no difference of their own, and are left
// out of the mean.
PerceptualMetric flip(const Image& test, const Image& reference,
                      const std::vector<bool>* includePixel = nullptr,
                      const FlipViewing& viewing = {});

}  // namespace penumbra
