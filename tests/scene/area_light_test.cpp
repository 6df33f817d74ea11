#include "scene/area_light.h"

#include <functional>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

// Geometry is stored in float with coordinates of order 1: round trips through the bilinear
// map and its inverse lose a few float roundings (about 1e-7 each), amplified by the quad's
// shape by at most a small factor.
constexpr float kGeometryTolerance = 1e-5f;

// Texture means are accumulated in double and returned in float: one float rounding.
constexpr float kMeanTolerance = 1e-6f;

// Built by hand rather than with Image's constructor so these tests depend on this module only.
Image makeImage(int width, int height, const std::function<glm::vec4(int, int)>& pixel) {
  Image image;
  image.width = width;
  image.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.pixels.push_back(pixel(x, y));
  return image;
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

QuadLight lightFrom(const std::array<glm::vec3, 4>& corners,
                    std::optional<glm::vec3> emittingSidePoint = std::nullopt) {
  std::string problem;
  const auto light = makeQuadLight(corners, emittingSidePoint, problem);
  EXPECT_TRUE(light.has_value()) << problem;
  return light.value_or(QuadLight{});
}

std::string problemOf(const std::array<glm::vec3, 4>& corners) {
  std::string problem;
  EXPECT_FALSE(makeQuadLight(corners, std::nullopt, problem).has_value());
  return problem;
}

// A convex quad that is not a parallelogram, on the tilted plane z = 0.3 x + 0.2 y + 1.
std::array<glm::vec3, 4> tiltedTrapezoid() {
  const auto onPlane = [](float x, float y) { return glm::vec3(x, y, 0.3f * x + 0.2f * y + 1); };
  return {onPlane(0, 0), onPlane(2, 0), onPlane(2.5f, 1.5f), onPlane(-0.2f, 1)};
}

const std::array<glm::vec3, 4> kUnitSquare{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0),
                                           glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)};

TEST(AreaLight, PointAtMapsTheCornersAndIsBilinear) {
  const QuadLight light = lightFrom(tiltedTrapezoid());
  expectNear(light.pointAt({0, 0}), light.corners[0], 0);
  expectNear(light.pointAt({1, 0}), light.corners[1], 0);
  expectNear(light.pointAt({1, 1}), light.corners[2], 0);
  expectNear(light.pointAt({0, 1}), light.corners[3], 0);
  const glm::vec3 bottom = 0.75f * light.corners[0] + 0.25f * light.corners[1];
  const glm::vec3 top = 0.75f * light.corners[3] + 0.25f * light.corners[2];
  expectNear(light.pointAt({0.25f, 0.5f}), 0.5f * (bottom + top), kGeometryTolerance);
}

TEST(AreaLight, UvAtInvertsPointAtOnANonParallelogram) {
  const QuadLight light = lightFrom(tiltedTrapezoid());
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const glm::vec2 uv(static_cast<float>(i) / 10, static_cast<float>(j) / 10);
      const auto back = light.uvAt(light.pointAt(uv));
      ASSERT_TRUE(back.has_value()) << uv.x << " " << uv.y;
      EXPECT_NEAR(back->x, uv.x, kGeometryTolerance);
      EXPECT_NEAR(back->y, uv.y, kGeometryTolerance);
    }
  }
}

TEST(AreaLight, UvAtInvertsPointAtOnAParallelogram) {
  const QuadLight light =
      lightFrom({glm::vec3(0, 0, 1), glm::vec3(2, 0, 1), glm::vec3(3, 1, 0), glm::vec3(1, 1, 0)});
  for (const glm::vec2 uv : {glm::vec2(0.3f, 0.8f), glm::vec2(1, 0), glm::vec2(0.5f, 0.5f)}) {
    const auto back = light.uvAt(light.pointAt(uv));
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(back->x, uv.x, kGeometryTolerance);
    EXPECT_NEAR(back->y, uv.y, kGeometryTolerance);
  }
}

TEST(AreaLight, UvAtRejectsPointsOutsideTheQuad) {
  const QuadLight light = lightFrom(tiltedTrapezoid());
  // Bilinear extrapolation beyond each edge stays on the plane but leaves the quad.
  for (const glm::vec2 uv : {glm::vec2(1.2f, 0.5f), glm::vec2(-0.1f, 0.5f), glm::vec2(0.5f, 1.1f),
                             glm::vec2(0.5f, -0.05f)})
    EXPECT_FALSE(light.uvAt(light.pointAt(uv)).has_value()) << uv.x << " " << uv.y;
}

TEST(AreaLight, NormalFollowsCornerOrderAndIsFlippedTowardsAt) {
  EXPECT_EQ(lightFrom(kUnitSquare).normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(lightFrom(kUnitSquare, glm::vec3(0.5f, 0.5f, 3)).normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(lightFrom(kUnitSquare, glm::vec3(9, -4, -0.5f)).normal, glm::vec3(0, 0, -1));
}

TEST(AreaLight, AreaIsTheSumOfTheTwoTriangles) {
  EXPECT_FLOAT_EQ(lightFrom(kUnitSquare).area, 1.0f);
  // Trapezoid with parallel sides 2 and 1 at distance 1.
  EXPECT_FLOAT_EQ(lightFrom({glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(1.5f, 1, 0),
                             glm::vec3(0.5f, 1, 0)})
                      .area,
                  1.5f);
}

TEST(AreaLight, RejectsZeroArea) {
  EXPECT_EQ(
      problemOf({glm::vec3(0, 0, 0), glm::vec3(1, 1, 1), glm::vec3(2, 2, 2), glm::vec3(3, 3, 3)}),
      "zero area: the corners do not span a surface");
  EXPECT_EQ(problemOf({glm::vec3(1), glm::vec3(1), glm::vec3(1), glm::vec3(1)}),
            "zero area: the corners do not span a surface");
}

TEST(AreaLight, RejectsCornersOffThePlaneBeyondTheSpecLimit) {
  // The diagonal is sqrt(2), so the limit is 1.41e-4.
  auto corners = kUnitSquare;
  corners[2].z = 1e-4f;
  std::string problem;
  EXPECT_TRUE(makeQuadLight(corners, std::nullopt, problem).has_value()) << problem;
  corners[2].z = 2e-4f;
  EXPECT_EQ(problemOf(corners).rfind("corners not coplanar: pos3 is 0.0002 from the plane", 0), 0u)
      << problemOf(corners);
}

TEST(AreaLight, RejectsNonConvexOrder) {
  // pos3 and pos4 swapped: the outline crosses itself.
  EXPECT_EQ(problemOf({kUnitSquare[0], kUnitSquare[1], kUnitSquare[3], kUnitSquare[2]}),
            "non-convex corner order: the outline turns the other way at pos3 (list the corners "
            "in order around a convex quad)");
  // pos3 pushed inside the triangle of the others: a dart.
  EXPECT_EQ(problemOf({kUnitSquare[0], kUnitSquare[1], glm::vec3(0.3f, 0.3f, 0), kUnitSquare[3]}),
            "non-convex corner order: the outline turns the other way at pos3 (list the corners "
            "in order around a convex quad)");
  // Three corners on one line: a triangle, whose bilinear map is singular at pos2.
  EXPECT_EQ(
      problemOf({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 1, 0)}),
      "non-convex corner order: pos1, pos2 and pos3 are collinear");
}

TEST(AreaLight, TextureCellMeanWeighsTexelsByOverlap) {
  // 3x2 image: red is a checkerboard, green marks the top row, blue is column^2.
  const Image image = makeImage(3, 2, [](int x, int y) {
    return glm::vec4(static_cast<float>((x + y) % 2), y == 0 ? 1.0f : 0.0f,
                     static_cast<float>(x * x), 1.0f);
  });
  // u in [0.25, 0.75] overlaps the columns by 1/12, 1/3, 1/12; v in [0.2, 0.6] overlaps the
  // bottom row (image row 1) by 0.3 and the top row by 0.1; the rectangle's area is 0.2.
  // red:   (0.3 * (1/12 + 1/12) + 0.1 * 1/3) / 0.2 = 5/12
  // green: 0.1 * 0.5 / 0.2 = 1/4
  // blue:  (1/3 * 1 + 1/12 * 4) / 0.5 = 4/3
  expectNear(textureCellMean(image, {0.25f, 0.2f}, {0.75f, 0.6f}),
             {5.0f / 12.0f, 0.25f, 4.0f / 3.0f}, kMeanTolerance);
  expectNear(textureCellMean(image, {0, 0}, {1, 1}), {0.5f, 0.5f, 5.0f / 3.0f}, kMeanTolerance);
  // Inside one texel the mean is that texel: bottom-left is image row 1, column 0.
  expectNear(textureCellMean(image, {0.05f, 0.1f}, {0.2f, 0.3f}), {1, 0, 0}, kMeanTolerance);
}

TEST(AreaLight, VplsCoverTheGridInRowOrder) {
  const QuadLight light = lightFrom(tiltedTrapezoid());
  constexpr int kCells = 4;
  const auto vpls = makeVpls(light, glm::vec3(2, 3, 4), nullptr, kCells);
  ASSERT_EQ(vpls.size(), 16u);
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      const Vpl& vpl = vpls[static_cast<std::size_t>(j * kCells + i)];
      const glm::vec2 centre((static_cast<float>(i) + 0.5f) / kCells,
                             (static_cast<float>(j) + 0.5f) / kCells);
      expectNear(vpl.position, light.pointAt(centre), kGeometryTolerance);
      EXPECT_EQ(vpl.normal, light.normal);
      EXPECT_EQ(vpl.radiance, glm::vec3(2, 3, 4));
      EXPECT_FLOAT_EQ(vpl.area, light.area / 16);
    }
  }
}

TEST(AreaLight, VplsTakeTheTextureUprightWithTopRowAtVOne) {
  // Top image row red, bottom row blue.
  const Image image = makeImage(
      1, 2, [](int, int y) { return y == 0 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1); });
  const auto vpls = makeVpls(lightFrom(kUnitSquare), glm::vec3(2), &image, 2);
  ASSERT_EQ(vpls.size(), 4u);
  expectNear(vpls[0].radiance, {0, 0, 2}, kMeanTolerance);
  expectNear(vpls[1].radiance, {0, 0, 2}, kMeanTolerance);
  expectNear(vpls[2].radiance, {2, 0, 0}, kMeanTolerance);
  expectNear(vpls[3].radiance, {2, 0, 0}, kMeanTolerance);
}

TEST(AreaLight, VplPowerMatchesTheLightForAUniformTexture) {
  const QuadLight light = lightFrom(tiltedTrapezoid());
  const glm::vec4 texel(0.5f, 0.25f, 1.0f, 1.0f);
  const Image image = makeImage(5, 3, [&](int, int) { return texel; });
  const glm::vec3 emission(2, 3, 4);
  const auto vpls = makeVpls(light, emission, &image, 7);
  glm::dvec3 power(0.0);
  for (const Vpl& vpl : vpls)
    power += glm::dvec3(vpl.radiance) * static_cast<double>(vpl.area);
  const glm::dvec3 expected = glm::dvec3(emission * glm::vec3(texel)) * double{light.area};
  // 49 float terms, each within a few float roundings of its share.
  for (int channel = 0; channel < 3; ++channel)
    EXPECT_NEAR(power[channel] / expected[channel], 1.0, 1e-5) << channel;
}

}  // namespace
}  // namespace penumbra
