#include "image/metrics.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(CompareImages, IdenticalImagesHaveNoErrorAndInfinitePsnr) {
  Image image(3, 2, glm::vec4(0.25f, 0.5f, 2.0f, 1.0f));
  const ImageMetrics metrics = compareImages(image, image);
  EXPECT_EQ(metrics.pixelCount, 6u);
  EXPECT_EQ(metrics.rmse, 0.0);
  EXPECT_EQ(metrics.relativeMse, 0.0);
  EXPECT_EQ(metrics.mae, 0.0);
  EXPECT_EQ(metrics.maxError, 0.0);
  EXPECT_TRUE(std::isinf(metrics.psnr) && metrics.psnr > 0.0);
}

TEST(CompareImages, KnownDifferences) {
  // Per channel errors (a - b): pixel 0: 0.5, 0, 0; pixel 1: 0, -1, 0.
  Image reference(2, 1, glm::vec4(0.0f));
  reference.at(0, 0) = {1.0f, 2.0f, 0.0f, 1.0f};
  reference.at(1, 0) = {0.0f, 3.0f, 0.0f, 1.0f};
  Image image = reference;
  image.at(0, 0).r += 0.5f;
  image.at(1, 0).g -= 1.0f;

  const ImageMetrics metrics = compareImages(image, reference);
  EXPECT_EQ(metrics.pixelCount, 2u);
  const double mse = (0.25 + 1.0) / 6.0;
  EXPECT_NEAR(metrics.rmse, std::sqrt(mse), 1e-12);
  EXPECT_NEAR(metrics.relativeMse, (0.25 / (1.0 + 0.01) + 1.0 / (9.0 + 0.01)) / 6.0, 1e-12);
  EXPECT_NEAR(metrics.mae, 1.5 / 6.0, 1e-12);
  EXPECT_NEAR(metrics.maxError, 1.0, 1e-12);
  // The peak is the reference's largest RGB value, 3.
  EXPECT_NEAR(metrics.psnr, 10.0 * std::log10(9.0 / mse), 1e-9);
}

TEST(CompareImages, AlphaIsIgnored) {
  const Image reference(2, 2, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  const Image image(2, 2, glm::vec4(0.5f, 0.5f, 0.5f, 0.0f));
  EXPECT_EQ(compareImages(image, reference).maxError, 0.0);
}

TEST(CompareImages, BlackReferenceUsesPeakOne) {
  const Image reference(1, 1, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const Image image(1, 1, glm::vec4(0.1f, 0.1f, 0.1f, 1.0f));
  const ImageMetrics metrics = compareImages(image, reference);
  EXPECT_NEAR(metrics.psnr, 10.0 * std::log10(1.0 / 0.01), 1e-5);
  EXPECT_NEAR(metrics.relativeMse, 1.0, 1e-5);
}

TEST(CompareImages, SizeMismatchNamesBothSizes) {
  const Image a(64, 64);
  const Image b(32, 32);
  try {
    compareImages(a, b);
    FAIL() << "expected ImageError";
  } catch (const ImageError& error) {
    EXPECT_STREQ(error.what(), "images differ in size: 64x64 vs 32x32");
  }
}

TEST(CompareImages, MaskLeavesPixelsOut) {
  Image reference(2, 2, glm::vec4(1.0f));
  Image image = reference;
  image.at(1, 0) = glm::vec4(100.0f);  // left out below
  image.at(0, 1).b = 1.5f;             // counted
  const std::vector<bool> include{true, false, true, true};

  const ImageMetrics masked = compareImages(image, reference, &include);
  EXPECT_EQ(masked.pixelCount, 3u);
  EXPECT_NEAR(masked.maxError, 0.5, 1e-12);
  EXPECT_NEAR(masked.mae, 0.5 / 9.0, 1e-12);

  EXPECT_NEAR(compareImages(image, reference).maxError, 99.0, 1e-12);
}

TEST(CompareImages, MaskOfWrongLengthIsRejected) {
  const Image image(2, 2);
  const std::vector<bool> include{true, true};
  EXPECT_THROW(compareImages(image, image, &include), ImageError);
}

TEST(CompareImages, EmptyMaskCountsNothing) {
  const Image reference(2, 1, glm::vec4(1.0f));
  const Image image(2, 1, glm::vec4(0.0f));
  const std::vector<bool> include{false, false};
  const ImageMetrics metrics = compareImages(image, reference, &include);
  EXPECT_EQ(metrics.pixelCount, 0u);
  EXPECT_EQ(metrics.rmse, 0.0);
}

TEST(CompareImages, NanShowsInEveryMetric) {
  const Image reference(2, 1, glm::vec4(1.0f));
  Image image = reference;
  image.at(0, 0).g = std::numeric_limits<float>::quiet_NaN();
  image.at(1, 0).r = 2.0f;  // a finite error after the NaN must not hide it
  const ImageMetrics metrics = compareImages(image, reference);
  EXPECT_TRUE(std::isnan(metrics.rmse));
  EXPECT_TRUE(std::isnan(metrics.relativeMse));
  EXPECT_TRUE(std::isnan(metrics.psnr));
  EXPECT_TRUE(std::isnan(metrics.mae));
  EXPECT_TRUE(std::isnan(metrics.maxError));
}

// A linear value that `render`'s PNG tone map shows as `displayed` (in [0,1]).
float linearShownAs(float displayed) {
  return srgbToLinear(displayed);
}

Image greyImage(int width, int height, float displayed) {
  const float linear = linearShownAs(displayed);
  return Image(width, height, glm::vec4(linear, linear, linear, 1.0f));
}

// A grey checkerboard of displayed values mean + or - amplitude: a zero-mean pattern of variance
// amplitude^2 on a flat image.
Image checkerboard(int width, int height, float mean, float amplitude) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float linear = linearShownAs((x + y) % 2 == 0 ? mean + amplitude : mean - amplitude);
      image.at(x, y) = glm::vec4(linear, linear, linear, 1.0f);
    }
  }
  return image;
}

// Smooth gradients with a few hard edges and colours: structure for the metrics to look at.
Image testPattern(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float u = static_cast<float>(x) / static_cast<float>(width);
      const float v = static_cast<float>(y) / static_cast<float>(height);
      const float edge = x > width / 2 ? 0.6f : 0.1f;
      image.at(x, y) = glm::vec4(u * u, edge, v, 1.0f);
    }
  }
  return image;
}

constexpr double kC1 = 0.01 * 0.01;
constexpr double kC2 = 0.03 * 0.03;

TEST(StructuralSimilarity, ImageWithItselfIsExactlyOne) {
  const Image image = testPattern(40, 30);
  const PerceptualMetric ssim = structuralSimilarity(image, image);
  EXPECT_EQ(ssim.pixelCount, 1200u);
  EXPECT_EQ(ssim.mean, 1.0);
}

TEST(StructuralSimilarity, ConstantOffsetIsTheLuminanceTerm) {
  // Flat images have no variance, so SSIM is the luminance term (2 p q + C1) / (p^2 + q^2 + C1)
  // at every pixel, the border's cut-off windows included.
  const Image a = greyImage(24, 20, 0.6f);
  const Image b = greyImage(24, 20, 0.4f);
  const double p = linearToSrgb(linearShownAs(0.6f));
  const double q = linearToSrgb(linearShownAs(0.4f));
  const double expected = (2.0 * p * q + kC1) / (p * p + q * q + kC1);
  const PerceptualMetric ssim = structuralSimilarity(a, b);
  // Only float rounding of the tone map separates the two (about 1e-7).
  EXPECT_NEAR(ssim.mean, expected, 1e-6);
  for (const float value : ssim.map) {
    EXPECT_NEAR(value, expected, 1e-6);
  }
}

TEST(StructuralSimilarity, PatternOfKnownVarianceGivesTheFormula) {
  // The reference is flat (no variance, no covariance), the image adds a zero-mean pattern of
  // variance s^2: SSIM = C2 / (s^2 + C2) where the window sees the pattern's mean as 0. A
  // checkerboard's mean under the 11x11 sigma 1.5 Gaussian window is off by below 1e-7 of its
  // amplitude (the window all but cancels alternating signs), so away from the border, where the
  // window is whole, the formula holds to the tone map's float rounding (about 1e-7).
  constexpr float kAmplitude = 0.05f;
  const Image noisy = checkerboard(32, 32, 0.5f, kAmplitude);
  const Image flat = greyImage(32, 32, 0.5f);
  const double variance = static_cast<double>(kAmplitude) * kAmplitude;
  const double expected = kC2 / (variance + kC2);
  const PerceptualMetric ssim = structuralSimilarity(noisy, flat);
  for (int y = 5; y < 27; ++y) {
    for (int x = 5; x < 27; ++x) {
      EXPECT_NEAR(ssim.map[static_cast<std::size_t>(y) * 32 + x], expected, 1e-5) << x << "," << y;
    }
  }
  EXPECT_LT(ssim.mean, 0.5);  // the pattern is far from the flat image
}

TEST(StructuralSimilarity, IsSymmetricAndBelowOneForADifference) {
  const Image a = testPattern(32, 32);
  Image b = a;
  b.at(10, 10) = glm::vec4(1.0f);
  const double forward = structuralSimilarity(a, b).mean;
  EXPECT_LT(forward, 1.0);
  EXPECT_DOUBLE_EQ(forward, structuralSimilarity(b, a).mean);
}

// A test pattern and a copy of it that differs wildly on a 4 x 4 block, which the mask leaves out.
struct MaskedDifference {
  Image reference = testPattern(16, 16);
  Image image = reference;
  std::vector<bool> include = std::vector<bool>(256, true);

  MaskedDifference() {
    for (int y = 4; y < 8; ++y) {
      for (int x = 4; x < 8; ++x) {
        image.at(x, y) = glm::vec4(50.0f, 0.0f, 3.0f, 1.0f);
        include[static_cast<std::size_t>(y) * 16 + x] = false;
      }
    }
  }
};

TEST(StructuralSimilarity, PixelsLeftOutAreLeftOutOfEveryWindow) {
  // Only the left-out pixels differ: they must change neither the mean nor their neighbours.
  const MaskedDifference images;
  const PerceptualMetric ssim =
      structuralSimilarity(images.image, images.reference, &images.include);
  EXPECT_EQ(ssim.pixelCount, 240u);
  EXPECT_EQ(ssim.mean, 1.0);
  EXPECT_LT(structuralSimilarity(images.image, images.reference).mean, 1.0);
}

TEST(StructuralSimilarity, SizeMismatchThrows) {
  EXPECT_THROW(structuralSimilarity(Image(4, 4), Image(4, 5)), ImageError);
}

TEST(Flip, DefaultViewingIsAbout67PixelsPerDegree) {
  // 0.7 m * 3840 px / 0.7 m * pi / 180.
  EXPECT_NEAR(FlipViewing{}.pixelsPerDegree(), 67.0206, 1e-3);
}

TEST(Flip, IdenticalImagesAreExactlyZero) {
  const Image image = testPattern(40, 30);
  const PerceptualMetric result = flip(image, image);
  EXPECT_EQ(result.pixelCount, 1200u);
  EXPECT_EQ(result.mean, 0.0);
}

// A vertical black-white edge at column `edgeColumn`, on a 64x32 image.
Image edgeImage(int edgeColumn) {
  Image image(64, 32, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  for (int y = 0; y < 32; ++y) {
    for (int x = edgeColumn; x < 64; ++x) {
      image.at(x, y) = glm::vec4(1.0f);
    }
  }
  return image;
}

TEST(Flip, VisibleEdgeShiftScoresFarAboveAnInvisibleChange) {
  const Image reference = edgeImage(32);
  // Two pixels of shift at 67 pixels per degree is 0.03 degrees: plainly seen when flipping.
  const double shifted = flip(edgeImage(34), reference).mean;
  // The same two columns 1% darker instead: about 0.4 in CIELAB lightness, under the 1 unit
  // commonly taken as just noticeable, where the shift changes them by 100.
  Image dimmed = reference;
  for (int y = 0; y < 32; ++y) {
    for (int x = 32; x < 34; ++x) {
      dimmed.at(x, y) = glm::vec4(0.99f, 0.99f, 0.99f, 1.0f);
    }
  }
  const double invisible = flip(dimmed, reference).mean;
  EXPECT_GT(invisible, 0.0);
  // FLIP grows with the difference faster than linearly at an edge (the feature term), so a
  // change 250 times larger in lightness scores well over 10 times higher.
  EXPECT_GT(shifted, 10.0 * invisible) << shifted << " vs " << invisible;
  // The shift covers 2 of 64 columns with errors near 1: a mean of at least 2/64 of that.
  EXPECT_GT(shifted, 0.9 * 2.0 / 64.0);
}

TEST(Flip, BlackAgainstWhiteIsNearTheTopOfTheScale) {
  const Image black(16, 16, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const Image white(16, 16, glm::vec4(1.0f));
  const double value = flip(black, white).mean;
  // Lightness 0 against 100 is past the compression point (p_c of the green-blue distance), so
  // each pixel maps above p_t = 0.95 and never above 1.
  EXPECT_GT(value, 0.95);
  EXPECT_LE(value, 1.0);
}

TEST(Flip, PixelsLeftOutAddNoDifference) {
  const MaskedDifference images;
  const PerceptualMetric masked = flip(images.image, images.reference, &images.include);
  EXPECT_EQ(masked.pixelCount, 240u);
  EXPECT_EQ(masked.mean, 0.0);
  EXPECT_GT(flip(images.image, images.reference).mean, 0.0);
}

TEST(PerceptualMetrics, NanShowsInBoth) {
  const Image reference = testPattern(8, 8);
  Image image = reference;
  image.at(3, 3).g = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(structuralSimilarity(image, reference).mean));
  EXPECT_TRUE(std::isnan(flip(image, reference).mean));
}

}  // namespace
}  // namespace penumbra
