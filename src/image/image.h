#pragma once
// Linear RGBA float images in memory, and their files: OpenEXR and Radiance HDR are
// linear; 8-bit formats (PNG, JPEG, ...) are sRGB encoded on disk.

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra {

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Row 0 is the top row of the picture, as in every image file.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> pixels;

  Image() = default;
  Image(int width, int height, glm::vec4 fill = glm::vec4(0.0f));

  glm::vec4& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec4& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
  bool empty() const { return pixels.empty(); }
};

enum class Wrap { Repeat, ClampToEdge };

// Bilinear reconstruction at texture coordinate uv, GL conventions: texel centres at
// ((i + 0.5) / width, (j + 0.5) / height) and v = 0 at the bottom row of the picture.
glm::vec4 sampleBilinear(const Image& image, glm::vec2 uv, Wrap wrap);

float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// Reads any format OpenImageIO knows; 8-bit data is decoded from sRGB to linear.
// Grey images are expanded to RGB; a missing alpha is 1. Only the first four channels are read,
// and images beyond 16384 pixels on a side or 8192x8192 pixels in all are rejected. Throws
// ImageError naming the file.
Image loadImage(const std::filesystem::path& file);
// The same for an image file's bytes in memory (a texture embedded in a model), in the format
// that `formatExtension` names ("png", "jpg", ...); `name` names the image in messages.
Image decodeImage(std::span<const std::uint8_t> bytes, const std::string& name,
                  const std::string& formatExtension);

struct SaveOptions {
  // PNG and other 8-bit outputs store srgb(clamp(linear * 2^exposure)); EXR stores linear values.
  float exposure = 0.0f;
};

// Chooses the format by extension (.exr linear float RGB, .png/.jpg tone-mapped 8-bit sRGB).
// Writes a temporary file beside the target and renames it, so a failure never leaves a
// half-written file. Throws ImageError naming the file.
void saveImage(const Image& image, const std::filesystem::path& file,
               const SaveOptions& options = {});

// One layer of a multi-layer EXR, stored as the channels NAME.R, NAME.G and NAME.B.
struct ImageLayer {
  std::string name;
  const Image* image = nullptr;
};

// Header attributes of an EXR: texts, and 4x4 matrices (OpenEXR's m44f; glm's column-major
// memory is Imath's row-vector layout, so a matrix reads back as the same transform).
struct ExrMetadata {
  std::vector<std::pair<std::string, std::string>> strings;
  std::vector<std::pair<std::string, glm::mat4>> matrices;
};

// Writes `radiance` as the channels R, G, B followed by each layer's, all of its size, with the
// metadata in the header; atomic like saveImage. Throws ImageError naming the file.
void saveLayeredExr(const Image& radiance, const std::vector<ImageLayer>& layers,
                    const ExrMetadata& metadata, const std::filesystem::path& file);

// Rounds srgb(clamp(linear * scale)) to 8 bits, as 8-bit outputs store it; NaN becomes 0.
std::uint8_t encode8BitSrgb(float linear, float scale);

// A temporary name beside `file` that no other writer picks: writers fill it and rename it to
// `file` on success, so a crash leaves only a stray temporary and never a truncated file.
std::filesystem::path temporaryPathFor(const std::filesystem::path& file);

}  // namespace penumbra
