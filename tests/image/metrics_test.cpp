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

}  // namespace
}  // namespace penumbra
