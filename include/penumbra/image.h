#pragma once
// Images in CPU memory: linear RGBA float, as the renderer computes them.

#include <filesystem>
#include <vector>

namespace penumbra::api {

struct Image {
  int width = 0;
  int height = 0;
  // width * height * 4 floats, RGBA, row by row from the top row of the picture.
  std::vector<float> rgba;

  const float* pixel(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)) *
                 4];
  }
};

// By extension: .exr stores linear floats, .png and .jpg srgb(clamp(value * 2^exposure)) in 8 bits.
// The file appears complete or not at all. Throws Error (Output).
void saveImage(const Image& image, const std::filesystem::path& file, float exposure = 0.0f);
// Any format OpenImageIO reads; 8-bit files are decoded from sRGB. Throws Error (BadInput).
Image loadImage(const std::filesystem::path& file);

}  // namespace penumbra::api
