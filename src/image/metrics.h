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

}  // namespace penumbra
