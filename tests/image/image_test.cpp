#include "image/image.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "test_files.h"

namespace penumbra {
namespace {

// Writes raw pixel data with OpenImageIO, for layouts saveImage never produces.
void writeRaw(const std::filesystem::path& file, int width, int height, int channels,
              OIIO::TypeDesc format, const void* data, const std::string& colorSpace = "") {
  auto output = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(output);
  OIIO::ImageSpec spec(width, height, channels, format);
  if (!colorSpace.empty())
    spec.attribute("oiio:ColorSpace", colorSpace);
  ASSERT_TRUE(output->open(file.string(), spec));
  ASSERT_TRUE(output->write_image(format, data));
  ASSERT_TRUE(output->close());
}

TEST(ImageSrgb, KnownValuesOfTheExactCurve) {
  // Reference values of the piecewise sRGB definition, to the printed digits.
  EXPECT_NEAR(srgbToLinear(128.0f / 255.0f), 0.2158605f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-9f);
  EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
  EXPECT_NEAR(linearToSrgb(0.5f), 0.7353570f, 1e-6f);
  EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
}

TEST(ImageSrgb, EncodeInvertsDecode) {
  for (int i = 0; i <= 255; ++i) {
    const float encoded = static_cast<float>(i) / 255.0f;
    // A few float ulps of pow() rounding on each way.
    EXPECT_NEAR(linearToSrgb(srgbToLinear(encoded)), encoded, 2e-6f) << i;
  }
}

TEST(ImageFile, Png8BitIsDecodedFromSrgb) {
  const auto directory = test::scratchDirectory();
  const std::vector<std::uint8_t> bytes = {128, 0, 255, 64, 255, 32};
  writeRaw(directory / "known.png", 2, 1, 3, OIIO::TypeDesc::UINT8, bytes.data());
  const Image image = loadImage(directory / "known.png");
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 1);
  // 8-bit input: the decoded value only has to match the curve at the stored byte.
  EXPECT_NEAR(image.at(0, 0).r, 0.2158605f, 1e-6f);
  EXPECT_NEAR(image.at(0, 0).g, 0.0f, 1e-6f);
  EXPECT_NEAR(image.at(0, 0).b, 1.0f, 1e-6f);
  EXPECT_NEAR(image.at(1, 0).r, srgbToLinear(64.0f / 255.0f), 1e-6f);
  EXPECT_FLOAT_EQ(image.at(1, 0).a, 1.0f);
}

TEST(ImageFile, PngDeclaredLinearIsNotDecoded) {
  const auto directory = test::scratchDirectory();
  const std::vector<std::uint8_t> bytes = {128, 128, 128};
  // OpenImageIO writes a gAMA chunk of 1.0 for a linear PNG.
  writeRaw(directory / "linear.png", 1, 1, 3, OIIO::TypeDesc::UINT8, bytes.data(), "Linear");
  // 128 / 255 up to float rounding.
  EXPECT_NEAR(loadImage(directory / "linear.png").at(0, 0).r, 128.0f / 255.0f, 1e-6f);
}

TEST(ImageFile, GreyIsExpandedAndAlphaKept) {
  const auto directory = test::scratchDirectory();
  const std::vector<std::uint8_t> grey = {128, 255};
  writeRaw(directory / "grey.png", 2, 1, 1, OIIO::TypeDesc::UINT8, grey.data());
  const Image greyImage = loadImage(directory / "grey.png");
  // Same decoding as the RGB case: exact up to float rounding.
  EXPECT_NEAR(greyImage.at(0, 0).r, 0.2158605f, 1e-6f);
  EXPECT_EQ(greyImage.at(0, 0).g, greyImage.at(0, 0).r);
  EXPECT_EQ(greyImage.at(0, 0).b, greyImage.at(0, 0).r);
  EXPECT_FLOAT_EQ(greyImage.at(0, 0).a, 1.0f);

  const std::vector<std::uint8_t> rgba = {255, 255, 255, 51};
  writeRaw(directory / "alpha.png", 1, 1, 4, OIIO::TypeDesc::UINT8, rgba.data());
  // Alpha is linear coverage, stored in 8 bits: 51 / 255 = 0.2 up to float rounding.
  EXPECT_NEAR(loadImage(directory / "alpha.png").at(0, 0).a, 0.2f, 1e-6f);
}

TEST(ImageFile, SixteenBitPngIsDecodedFromSrgb) {
  const auto directory = test::scratchDirectory();
  const std::vector<std::uint16_t> values = {32768, 0, 65535};
  writeRaw(directory / "deep.png", 1, 1, 3, OIIO::TypeDesc::UINT16, values.data());
  // 16-bit input: exact up to float rounding of 32768 / 65535.
  EXPECT_NEAR(loadImage(directory / "deep.png").at(0, 0).r, srgbToLinear(32768.0f / 65535.0f),
              1e-6f);
}

TEST(ImageFile, ExrRoundTripIsExact) {
  const auto directory = test::scratchDirectory();
  Image image(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      image.at(x, y) =
          glm::vec4(1234.5678f * static_cast<float>(x + 1), 1e-7f * static_cast<float>(y),
                    -0.3f + 0.1f * static_cast<float>(x * y), 1.0f);
  saveImage(image, directory / "exact.exr");
  const Image loaded = loadImage(directory / "exact.exr");
  ASSERT_EQ(loaded.width, 3);
  ASSERT_EQ(loaded.height, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      EXPECT_EQ(loaded.at(x, y), image.at(x, y)) << x << "," << y;
}

TEST(ImageFile, PngRoundTripQuantisesThroughSrgb) {
  const auto directory = test::scratchDirectory();
  Image image(1, 1, glm::vec4(srgbToLinear(128.0f / 255.0f), 0.5f, 0.0f, 1.0f));
  saveImage(image, directory / "round.png");
  const Image loaded = loadImage(directory / "round.png");
  // The first channel sits exactly on an 8-bit code, so it survives up to float rounding.
  EXPECT_NEAR(loaded.at(0, 0).r, image.at(0, 0).r, 1e-6f);
  // Half an 8-bit sRGB step at linear 0.5 is 0.0030.
  EXPECT_NEAR(loaded.at(0, 0).g, 0.5f, 0.003f);
  EXPECT_FLOAT_EQ(loaded.at(0, 0).b, 0.0f);
}

TEST(ImageFile, JpegIsEightBitSrgb) {
  const auto directory = test::scratchDirectory();
  saveImage(Image(8, 8, glm::vec4(0.5f, 0.25f, 0.125f, 1.0f)), directory / "flat.jpg");
  const Image loaded = loadImage(directory / "flat.jpg");
  ASSERT_EQ(loaded.width, 8);
  // A flat colour survives JPEG up to a code or two of chroma rounding (0.006 per code at 0.5).
  EXPECT_NEAR(loaded.at(3, 3).r, 0.5f, 0.015f);
  EXPECT_NEAR(loaded.at(3, 3).g, 0.25f, 0.015f);
  EXPECT_NEAR(loaded.at(3, 3).b, 0.125f, 0.015f);
}

TEST(ImageFile, ExposureScalesAndClampsPng) {
  const auto directory = test::scratchDirectory();
  Image image(2, 1);
  image.at(0, 0) = glm::vec4(0.125f, 0.25f, 2.0f, 1.0f);
  image.at(1, 0) = glm::vec4(-1.0f, 0.0f, 0.0f, 1.0f);
  saveImage(image, directory / "bright.png", {.exposure = 2.0f});
  const Image loaded = loadImage(directory / "bright.png");
  // 0.125 * 4 = 0.5; half an 8-bit sRGB step there is 0.0030.
  EXPECT_NEAR(loaded.at(0, 0).r, 0.5f, 0.003f);
  EXPECT_FLOAT_EQ(loaded.at(0, 0).g, 1.0f);
  EXPECT_FLOAT_EQ(loaded.at(0, 0).b, 1.0f);
  EXPECT_FLOAT_EQ(loaded.at(1, 0).r, 0.0f);
}

TEST(ImageFile, ExposureDoesNotChangeExr) {
  const auto directory = test::scratchDirectory();
  const Image image(1, 1, glm::vec4(3.0f, 0.5f, 0.25f, 1.0f));
  saveImage(image, directory / "linear.exr", {.exposure = 3.0f});
  EXPECT_EQ(loadImage(directory / "linear.exr").at(0, 0), image.at(0, 0));
}

TEST(ImageFile, FailedSaveLeavesNothing) {
  const auto directory = test::scratchDirectory();
  const auto target = directory / "missing" / "out.png";
  try {
    saveImage(Image(2, 2), target);
    FAIL() << "saving into a missing directory succeeded";
  } catch (const ImageError& error) {
    EXPECT_NE(std::string(error.what()).find(target.string()), std::string::npos) << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(directory / "missing"));
  EXPECT_TRUE(std::filesystem::is_empty(directory));
}

TEST(ImageFile, SaveLeavesOnlyTheTarget) {
  const auto directory = test::scratchDirectory();
  saveImage(Image(2, 2, glm::vec4(0.5f)), directory / "out.png");
  saveImage(Image(2, 2, glm::vec4(0.25f)), directory / "out.png");
  std::vector<std::filesystem::path> entries;
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    entries.push_back(entry.path().filename());
  EXPECT_EQ(entries, std::vector<std::filesystem::path>{"out.png"});
  // The second save replaced the first: half an 8-bit sRGB step at 0.25 is 0.0020.
  EXPECT_NEAR(loadImage(directory / "out.png").at(0, 0).r, 0.25f, 0.002f);
}

TEST(ImageFile, UnknownExtensionIsAnError) {
  const auto directory = test::scratchDirectory();
  EXPECT_THROW(saveImage(Image(1, 1), directory / "out.xyz"), ImageError);
  EXPECT_THROW(saveImage(Image(1, 1), directory / "out"), ImageError);
  EXPECT_TRUE(std::filesystem::is_empty(directory));
}

TEST(ImageFile, UnreadableFileNamesTheFile) {
  const auto directory = test::scratchDirectory();
  const auto missing = directory / "absent.png";
  const auto garbage = test::writeFile(directory, "garbage.png", "this is not a PNG");
  for (const auto& file : {missing, garbage}) {
    try {
      loadImage(file);
      FAIL() << "loading " << file << " succeeded";
    } catch (const ImageError& error) {
      EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
    }
  }
}

// A 2x2 picture: top row (file row 0) = a b, bottom row = c d.
Image twoByTwo() {
  Image image(2, 2);
  image.at(0, 0) = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  image.at(1, 0) = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
  image.at(0, 1) = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  image.at(1, 1) = glm::vec4(1.0f, 1.0f, 1.0f, 1.0f);
  return image;
}

TEST(ImageSample, TexelCentresReturnTexels) {
  const Image image = twoByTwo();
  for (const Wrap wrap : {Wrap::Repeat, Wrap::ClampToEdge}) {
    // v = 0 is the bottom row, i.e. file row 1.
    EXPECT_EQ(sampleBilinear(image, {0.25f, 0.25f}, wrap), image.at(0, 1));
    EXPECT_EQ(sampleBilinear(image, {0.75f, 0.25f}, wrap), image.at(1, 1));
    EXPECT_EQ(sampleBilinear(image, {0.25f, 0.75f}, wrap), image.at(0, 0));
    EXPECT_EQ(sampleBilinear(image, {0.75f, 0.75f}, wrap), image.at(1, 0));
  }
}

TEST(ImageSample, InterpolatesBetweenCentres) {
  const Image image = twoByTwo();
  const glm::vec4 mean =
      0.25f * (image.at(0, 0) + image.at(1, 0) + image.at(0, 1) + image.at(1, 1));
  // Weights of 0.5 and 0.25 are exact in binary floating point.
  EXPECT_EQ(sampleBilinear(image, {0.5f, 0.5f}, Wrap::ClampToEdge), mean);
  EXPECT_EQ(sampleBilinear(image, {0.5f, 0.75f}, Wrap::ClampToEdge),
            0.5f * (image.at(0, 0) + image.at(1, 0)));
  // A quarter of the way from the left centre (u = 0.25) to the right one (u = 0.75).
  const glm::vec4 quarter = sampleBilinear(image, {0.375f, 0.25f}, Wrap::ClampToEdge);
  EXPECT_EQ(quarter, 0.75f * image.at(0, 1) + 0.25f * image.at(1, 1));
}

TEST(ImageSample, EdgesWrapOrClamp) {
  const Image image = twoByTwo();
  // At u = 0 the left texel centre is half a texel away: clamping repeats the left texel,
  // repeating blends it half and half with the right one.
  EXPECT_EQ(sampleBilinear(image, {0.0f, 0.25f}, Wrap::ClampToEdge), image.at(0, 1));
  EXPECT_EQ(sampleBilinear(image, {0.0f, 0.25f}, Wrap::Repeat),
            0.5f * (image.at(0, 1) + image.at(1, 1)));
  EXPECT_EQ(sampleBilinear(image, {1.25f, -0.25f}, Wrap::Repeat), image.at(0, 0));
  EXPECT_EQ(sampleBilinear(image, {5.0f, 7.0f}, Wrap::ClampToEdge), image.at(1, 0));
  EXPECT_EQ(sampleBilinear(image, {-4e9f, 0.75f}, Wrap::ClampToEdge), image.at(0, 0));
  // 1e9 + 0.25 is not representable in float: the repeat of a huge u only has to stay finite.
  const glm::vec4 far = sampleBilinear(image, {1e9f, 0.25f}, Wrap::Repeat);
  EXPECT_TRUE(std::isfinite(far.r) && std::isfinite(far.g) && std::isfinite(far.b));
}

TEST(ImageSample, TopRowOfTheFileIsNearVOne) {
  const auto directory = test::scratchDirectory();
  Image image(1, 4, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  image.at(0, 0) = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  saveImage(image, directory / "stripe.png");
  const Image loaded = loadImage(directory / "stripe.png");
  EXPECT_EQ(sampleBilinear(loaded, {0.5f, 0.99f}, Wrap::ClampToEdge), glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(sampleBilinear(loaded, {0.5f, 0.01f}, Wrap::ClampToEdge), glm::vec4(0, 0, 1, 1));
}

}  // namespace
}  // namespace penumbra
