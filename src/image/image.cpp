#include "image/image.h"

#include <unistd.h>

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <system_error>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace penumbra {

namespace {

// OpenGL 4.5 guarantees textures of 16384 texels on a side (GL_MAX_TEXTURE_SIZE), so longer
// sides could not be textures on every implementation. The pixel count bounds the memory of one
// load to 2 GiB (the file's values and the RGBA float image, 16 bytes a pixel each).
constexpr int kMaxImageSide = 16384;
constexpr std::int64_t kMaxImagePixels = std::int64_t{8192} * 8192;
constexpr int kMaxReadChannels = 4;

// Third-party readers under OIIO print their own messages on stderr (libpng: "libpng error:
// IDAT: Read error" before the error OIIO then returns). While one is alive, stderr goes to a
// temporary file; on a successful read its lines are forwarded as warnings naming the image, and
// after a failure they are dropped, since the ImageError carries the same error. The redirection
// is process-wide, so images are read one at a time (the scene loader and `compare` do).
class StderrCapture {
 public:
  StderrCapture() : file_(std::tmpfile()) {
    std::fflush(stderr);
    saved_ = dup(STDERR_FILENO);
    if (file_ != nullptr && saved_ >= 0)
      dup2(fileno(file_), STDERR_FILENO);
  }
  ~StderrCapture() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      dup2(saved_, STDERR_FILENO);
      close(saved_);
    }
    if (file_ != nullptr)
      std::fclose(file_);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // Restores stderr and prints what was captured, each line a warning about `file`.
  void forwardAsWarnings(const std::filesystem::path& file) {
    std::fflush(stderr);
    if (saved_ < 0 || file_ == nullptr)
      return;
    dup2(saved_, STDERR_FILENO);
    std::rewind(file_);
    char line[1024];
    while (std::fgets(line, sizeof line, file_) != nullptr) {
      std::string text(line);
      while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
        text.pop_back();
      if (!text.empty())
        std::fprintf(stderr, "penumbra: warning: %s: %s\n", file.string().c_str(), text.c_str());
    }
  }

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

// OIIO's error texts can hold several lines (one per library that reported); every error is one
// line on stderr.
std::string oneLine(std::string text) {
  while (!text.empty() && text.back() == '\n')
    text.pop_back();
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at))
    text.replace(at, 1, "; ");
  return text;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string lowercaseExtension(const std::filesystem::path& file) {
  return lowercase(file.extension().string());
}

// Integer pixel data is sRGB encoded unless the file declares it linear (e.g. a PNG whose gAMA
// chunk says 1.0). Other gamma curves that OIIO reports are rare enough to be read as sRGB.
bool storesSrgb(const OIIO::ImageSpec& spec) {
  if (spec.format.is_floating_point())
    return false;
  const std::string colorSpace = lowercase(spec.get_string_attribute("oiio:ColorSpace"));
  return colorSpace.find("linear") == std::string::npos;
}

int wrapIndex(int index, int size, Wrap wrap) {
  if (wrap == Wrap::ClampToEdge)
    return std::clamp(index, 0, size - 1);
  const int remainder = index % size;
  return remainder < 0 ? remainder + size : remainder;
}

}  // namespace

// A name beside the target that no other writer picks, so a crash leaves only a stray temporary
// and never a truncated file under the target's name.
std::filesystem::path temporaryPathFor(const std::filesystem::path& file) {
  std::random_device entropy;
  const std::uint64_t token = (static_cast<std::uint64_t>(entropy()) << 32) ^ entropy();
  return file.parent_path() / ("." + file.filename().string() + ".tmp" + std::to_string(token));
}

std::uint8_t encode8BitSrgb(float linear, float scale) {
  float value = linear * scale;
  if (!(value > 0.0f))
    value = 0.0f;
  value = std::min(value, 1.0f);
  return static_cast<std::uint8_t>(std::lround(linearToSrgb(value) * 255.0f));
}

Image::Image(int imageWidth, int imageHeight, glm::vec4 fill)
    : width(imageWidth), height(imageHeight) {
  if (imageWidth < 0 || imageHeight < 0)
    throw ImageError("image size " + std::to_string(imageWidth) + "x" +
                     std::to_string(imageHeight) + " is negative");
  pixels.assign(static_cast<std::size_t>(imageWidth) * static_cast<std::size_t>(imageHeight), fill);
}

float srgbToLinear(float encoded) {
  if (encoded <= 0.04045f)
    return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  if (linear <= 0.0031308f)
    return linear * 12.92f;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

glm::vec4 sampleBilinear(const Image& image, glm::vec2 uv, Wrap wrap) {
  assert(!image.empty());
  // Repeat is periodic, so only the fraction matters; clamping the texel coordinate to one texel
  // beyond the edges changes no result and keeps huge or NaN coordinates out of the int casts.
  if (wrap == Wrap::Repeat)
    uv -= glm::floor(uv);
  const auto texelCoordinate = [](float coordinate, int size) {
    const float texel = coordinate * static_cast<float>(size) - 0.5f;
    return std::fmin(std::fmax(texel, -1.0f), static_cast<float>(size));
  };
  // Texel centres on integers; y counts rows from the bottom.
  const float x = texelCoordinate(uv.x, image.width);
  const float yFromBottom = texelCoordinate(uv.y, image.height);
  const float x0 = std::floor(x);
  const float y0 = std::floor(yFromBottom);
  const float fx = x - x0;
  const float fy = yFromBottom - y0;
  const int left = wrapIndex(static_cast<int>(x0), image.width, wrap);
  const int right = wrapIndex(static_cast<int>(x0) + 1, image.width, wrap);
  const int bottom = image.height - 1 - wrapIndex(static_cast<int>(y0), image.height, wrap);
  const int top = image.height - 1 - wrapIndex(static_cast<int>(y0) + 1, image.height, wrap);
  const glm::vec4 lower = glm::mix(image.at(left, bottom), image.at(right, bottom), fx);
  const glm::vec4 upper = glm::mix(image.at(left, top), image.at(right, top), fx);
  return glm::mix(lower, upper, fy);
}

namespace {

// The pixels of an opened image; `name` names it in messages.
Image readOpenedImage(OIIO::ImageInput& input, const std::string& name) {
  const OIIO::ImageSpec& spec = input.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw ImageError("image " + name + " has no pixels");
  // The header may claim any size, so it is checked before allocating (a 200-byte PNG can ask
  // for 120 GB: tests/data/fuzz).
  if (spec.width > kMaxImageSide || spec.height > kMaxImageSide ||
      std::int64_t{spec.width} * spec.height > kMaxImagePixels) {
    throw ImageError("image " + name + " is " + std::to_string(spec.width) + "x" +
                     std::to_string(spec.height) + "; images are limited to " +
                     std::to_string(kMaxImageSide) + " pixels on a side and " +
                     std::to_string(kMaxImagePixels) + " pixels (8192x8192) in all");
  }

  // Colour and alpha are the first four channels in every format read here; further ones (EXR
  // layers) would only multiply the memory, so they are not read.
  const int readChannels = std::min(spec.nchannels, kMaxReadChannels);
  const auto channels = static_cast<std::size_t>(readChannels);
  std::vector<float> values(static_cast<std::size_t>(spec.width) *
                            static_cast<std::size_t>(spec.height) * channels);
  if (!input.read_image(0, 0, 0, readChannels, OIIO::TypeDesc::FLOAT, values.data()))
    throw ImageError("cannot read image " + name + ": " + oneLine(input.geterror()));

  const bool srgb = storesSrgb(spec);
  const bool grey = spec.nchannels < 3;
  const int alphaChannel = spec.alpha_channel >= 0 && spec.alpha_channel < readChannels
                               ? spec.alpha_channel
                               : (spec.nchannels == 2 ? 1 : -1);
  const auto decode = [srgb](float encoded) { return srgb ? srgbToLinear(encoded) : encoded; };

  Image image(spec.width, spec.height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float* source = &values[i * channels];
    glm::vec4& pixel = image.pixels[i];
    pixel.r = decode(source[0]);
    pixel.g = grey ? pixel.r : decode(source[1]);
    pixel.b = grey ? pixel.r : decode(source[2]);
    pixel.a = alphaChannel >= 0 ? source[alphaChannel] : 1.0f;
  }
  return image;
}

}  // namespace

Image loadImage(const std::filesystem::path& file) {
  StderrCapture libraryMessages;
  auto input = OIIO::ImageInput::open(file.string());
  if (!input)
    throw ImageError("cannot read image " + file.string() + ": " + oneLine(OIIO::geterror()));
  Image image = readOpenedImage(*input, file.string());
  libraryMessages.forwardAsWarnings(file.string());
  return image;
}

Image decodeImage(std::span<const std::uint8_t> bytes, const std::string& name,
                  const std::string& formatExtension) {
  StderrCapture libraryMessages;
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  // OpenImageIO picks the reader by the name's extension and reads the bytes through the proxy.
  auto input = OIIO::ImageInput::open("memory." + formatExtension, nullptr, &reader);
  if (!input)
    throw ImageError("cannot read image " + name + ": " + oneLine(OIIO::geterror()));
  Image image = readOpenedImage(*input, name);
  libraryMessages.forwardAsWarnings(name);
  return image;
}

namespace {

// Writes `data` (in spec.format, the channels of each pixel together, row 0 at the top) to a
// temporary name beside `file` and renames it; throws ImageError naming the file.
void writeThroughTemporary(const std::filesystem::path& file, const OIIO::ImageSpec& spec,
                           const void* data) {
  const std::filesystem::path temporary = temporaryPathFor(file);
  const auto fail = [&](const std::string& reason) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw ImageError("cannot save image " + file.string() + ": " + reason);
  };

  // The writer is chosen by the target's extension; the temporary name has none it could use.
  auto output = OIIO::ImageOutput::create(file.string());
  if (!output)
    fail(OIIO::geterror());
  if (!output->open(temporary.string(), spec))
    fail(output->geterror());
  if (!output->write_image(spec.format, data)) {
    const std::string reason = output->geterror();
    output->close();
    fail(reason);
  }
  if (!output->close())
    fail(output->geterror());
  output.reset();

  std::error_code renameError;
  std::filesystem::rename(temporary, file, renameError);
  if (renameError)
    fail(renameError.message());
}

}  // namespace

void saveImage(const Image& image, const std::filesystem::path& file, const SaveOptions& options) {
  const std::string extension = lowercaseExtension(file);
  const bool linearFloat = extension == ".exr";
  if (!linearFloat && extension != ".png" && extension != ".jpg" && extension != ".jpeg")
    throw ImageError("cannot save image " + file.string() + ": unknown extension '" + extension +
                     "' (use .exr, .png or .jpg)");
  if (image.empty())
    throw ImageError("cannot save image " + file.string() + ": image is empty");

  const std::size_t pixelCount = image.pixels.size();
  std::vector<float> floatValues;
  std::vector<std::uint8_t> byteValues;
  if (linearFloat) {
    floatValues.resize(pixelCount * 3);
    for (std::size_t i = 0; i < pixelCount; ++i)
      for (int c = 0; c < 3; ++c)
        floatValues[i * 3 + c] = image.pixels[i][c];
  } else {
    const float scale = std::exp2(options.exposure);
    byteValues.resize(pixelCount * 3);
    for (std::size_t i = 0; i < pixelCount; ++i)
      for (int c = 0; c < 3; ++c)
        byteValues[i * 3 + c] = encode8BitSrgb(image.pixels[i][c], scale);
  }
  const OIIO::TypeDesc format = linearFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  const void* data = linearFloat ? static_cast<const void*>(floatValues.data())
                                 : static_cast<const void*>(byteValues.data());

  OIIO::ImageSpec spec(image.width, image.height, 3, format);
  spec.attribute("oiio:ColorSpace", linearFloat ? "Linear" : "sRGB");
  writeThroughTemporary(file, spec, data);
}

void saveLayeredExr(const Image& radiance, const std::vector<ImageLayer>& layers,
                    const ExrMetadata& metadata, const std::filesystem::path& file) {
  if (lowercaseExtension(file) != ".exr")
    throw ImageError("cannot save image " + file.string() + ": layers need an .exr file");
  if (radiance.empty())
    throw ImageError("cannot save image " + file.string() + ": image is empty");
  std::vector<const Image*> sources = {&radiance};
  std::vector<std::string> channels = {"R", "G", "B"};
  for (const ImageLayer& layer : layers) {
    if (layer.image->width != radiance.width || layer.image->height != radiance.height)
      throw ImageError("cannot save image " + file.string() + ": layer '" + layer.name + "' is " +
                       std::to_string(layer.image->width) + "x" +
                       std::to_string(layer.image->height) + ", the image " +
                       std::to_string(radiance.width) + "x" + std::to_string(radiance.height));
    sources.push_back(layer.image);
    for (const char* channel : {".R", ".G", ".B"})
      channels.push_back(layer.name + channel);
  }
  const std::size_t channelCount = channels.size();
  const std::size_t pixelCount = radiance.pixels.size();
  std::vector<float> values(pixelCount * channelCount);
  for (std::size_t i = 0; i < pixelCount; ++i)
    for (std::size_t source = 0; source < sources.size(); ++source)
      for (int c = 0; c < 3; ++c)
        values[i * channelCount + source * 3 + static_cast<std::size_t>(c)] =
            sources[source]->pixels[i][c];

  OIIO::ImageSpec spec(radiance.width, radiance.height, static_cast<int>(channelCount),
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  spec.attribute("oiio:ColorSpace", "Linear");
  for (const auto& [name, value] : metadata.strings)
    spec.attribute(name, value);
  for (const auto& [name, matrix] : metadata.matrices)
    spec.attribute(name, OIIO::TypeMatrix44, &matrix[0][0]);
  writeThroughTemporary(file, spec, values.data());
}

}  // namespace penumbra
