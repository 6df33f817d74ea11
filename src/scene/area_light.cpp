#include "scene/area_light.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace penumbra {

namespace {

// Areas and corner turns are compared with the squared diagonal times this factor: below it
// they are within the rounding of float corner coordinates, so the shape is taken as flat.
constexpr double kFlatness = 1e-7;

// Spec rule: pos3 may lie at most this fraction of the quad's diagonal away from the plane of
// pos1, pos2 and pos4.
constexpr double kCoplanarity = 1e-4;

// How far outside [0,1]^2 uvAt still accepts a point: float corners and points carry about
// 1e-7 relative error, so points computed on an edge land slightly outside.
constexpr double kUvTolerance = 1e-5;

// z component of the cross product of two in-plane vectors.
double cross2(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}

std::array<glm::dvec3, 4> toDouble(const std::array<glm::vec3, 4>& corners) {
  return {glm::dvec3(corners[0]), glm::dvec3(corners[1]), glm::dvec3(corners[2]),
          glm::dvec3(corners[3])};
}

std::string cornerName(std::size_t index) {
  return "pos" + std::to_string(index % 4 + 1);
}

std::string formatNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Roots of a u^2 + b u + c = 0, computed without cancellation; a linear equation when a is 0.
std::vector<double> quadraticRoots(double a, double b, double c) {
  if (a == 0.0) {
    if (b == 0.0)
      return {};
    return {-c / b};
  }
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0)
    return {};
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  if (q == 0.0)
    return {0.0};  // b and c are both 0: a double root at 0
  return {c / q, q / a};
}

}  // namespace

glm::vec3 QuadLight::pointAt(glm::vec2 uv) const {
  const glm::vec3 bottom = glm::mix(corners[0], corners[1], uv.x);
  const glm::vec3 top = glm::mix(corners[3], corners[2], uv.x);
  return glm::mix(bottom, top, uv.y);
}

// Works in 2D coordinates of the quad's plane with pos1 at the origin, where the bilinear map is
// q = u e + v f + u v g (e = pos2, f = pos4, g = pos3 - pos2 - pos4). Then q - u e = v (f + u g),
// so q - u e is parallel to f + u g; their 2D cross product vanishing gives a quadratic in u:
//   cross(e,g) u^2 + (cross(e,f) - cross(q,g)) u - cross(q,f) = 0,
// which is linear for a parallelogram (g = 0). v then follows by projection on f + u g.
std::optional<glm::vec2> QuadLight::uvAt(glm::vec3 point) const {
  const auto [p1, p2, p3, p4] = toDouble(corners);
  const glm::dvec3 diagonal = p3 - p1;
  const glm::dvec3 planeNormal = glm::cross(diagonal, p4 - p2);
  if (glm::length(planeNormal) == 0.0)
    return std::nullopt;
  const glm::dvec3 axisX = glm::normalize(diagonal);
  const glm::dvec3 axisY = glm::cross(glm::normalize(planeNormal), axisX);
  // clang 14 (the fuzz build) cannot capture a structured binding, hence the named copy.
  const auto inPlane = [&, origin = p1](const glm::dvec3& position) {
    const glm::dvec3 offset = position - origin;
    return glm::dvec2(glm::dot(offset, axisX), glm::dot(offset, axisY));
  };

  const glm::dvec2 e = inPlane(p2);
  const glm::dvec2 f = inPlane(p4);
  const glm::dvec2 g = inPlane(p3) - e - f;
  const glm::dvec2 q = inPlane(glm::dvec3(point));

  for (const double u : quadraticRoots(cross2(e, g), cross2(e, f) - cross2(q, g), -cross2(q, f))) {
    if (u < -kUvTolerance || u > 1.0 + kUvTolerance)
      continue;
    const glm::dvec2 vDirection = f + u * g;
    const double lengthSquared = glm::dot(vDirection, vDirection);
    if (lengthSquared == 0.0)
      continue;
    const double v = glm::dot(q - u * e, vDirection) / lengthSquared;
    if (v < -kUvTolerance || v > 1.0 + kUvTolerance)
      continue;
    return glm::vec2(static_cast<float>(std::clamp(u, 0.0, 1.0)),
                     static_cast<float>(std::clamp(v, 0.0, 1.0)));
  }
  return std::nullopt;
}

std::optional<QuadLight> makeQuadLight(const std::array<glm::vec3, 4>& corners,
                                       const std::optional<glm::vec3>& emittingSidePoint,
                                       std::string& problem) {
  problem.clear();
  const std::array<glm::dvec3, 4> p = toDouble(corners);
  const double diagonal = std::max(glm::length(p[2] - p[0]), glm::length(p[3] - p[1]));
  const double flatLimit = kFlatness * diagonal * diagonal;

  const double area = 0.5 * (glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) +
                             glm::length(glm::cross(p[2] - p[0], p[3] - p[0])));
  // Written as a negation so that non-finite corners are rejected too.
  if (!(area > flatLimit)) {
    problem = "zero area: the corners do not span a surface";
    return std::nullopt;
  }

  const glm::dvec3 cornerNormal = glm::cross(p[1] - p[0], p[3] - p[0]);
  if (glm::length(cornerNormal) <= flatLimit) {
    problem = "non-convex corner order: pos2, pos1 and pos4 are collinear";
    return std::nullopt;
  }
  const glm::dvec3 normal = glm::normalize(cornerNormal);

  const double distance = std::abs(glm::dot(p[2] - p[0], normal));
  if (distance > kCoplanarity * diagonal) {
    problem = "corners not coplanar: pos3 is " + formatNumber(distance) +
              " from the plane of pos1, pos2 and pos4 (at most " +
              formatNumber(kCoplanarity * diagonal) + ", 1e-4 of the diagonal, is allowed)";
    return std::nullopt;
  }

  // The turn at pos1 is positive by the choice of the normal; a convex quad turns the same
  // way at every other corner.
  for (std::size_t corner = 1; corner < 4; ++corner) {
    const glm::dvec3 incoming = p[corner] - p[corner - 1];
    const glm::dvec3 outgoing = p[(corner + 1) % 4] - p[corner];
    const double turn = glm::dot(glm::cross(incoming, outgoing), normal);
    if (turn <= -flatLimit) {
      problem = "non-convex corner order: the outline turns the other way at " +
                cornerName(corner) + " (list the corners in order around a convex quad)";
      return std::nullopt;
    }
    if (turn < flatLimit) {
      problem = "non-convex corner order: " + cornerName(corner + 3) + ", " + cornerName(corner) +
                " and " + cornerName(corner + 1) + " are collinear";
      return std::nullopt;
    }
  }

  QuadLight light;
  light.corners = corners;
  light.normal = glm::vec3(normal);
  light.area = static_cast<float>(area);
  if (emittingSidePoint) {
    const glm::vec3 centre = 0.25f * (corners[0] + corners[1] + corners[2] + corners[3]);
    if (glm::dot(*emittingSidePoint - centre, light.normal) < 0.0f)
      light.normal = -light.normal;
  }
  return light;
}

// Texel x covers u in [x/W, (x+1)/W]; the image row r texels above the bottom one (image row
// H-1-r) covers v in [r/H, (r+1)/H]. A rectangle without area gives the texel at uvMin, and an
// empty image acts as no texture (T = 1).
glm::vec3 textureCellMean(const Image& texture, glm::vec2 uvMin, glm::vec2 uvMax) {
  if (texture.empty())
    return glm::vec3(1.0f);
  const int width = texture.width;
  const int height = texture.height;
  const double u0 = std::clamp(static_cast<double>(uvMin.x), 0.0, 1.0);
  const double u1 = std::clamp(static_cast<double>(uvMax.x), 0.0, 1.0);
  const double v0 = std::clamp(static_cast<double>(uvMin.y), 0.0, 1.0);
  const double v1 = std::clamp(static_cast<double>(uvMax.y), 0.0, 1.0);
  const auto texelIndex = [](double coordinate, int count) {
    return std::clamp(static_cast<int>(std::floor(coordinate * count)), 0, count - 1);
  };

  glm::dvec3 weightedSum(0.0);
  double weightTotal = 0.0;
  for (int rowFromBottom = texelIndex(v0, height); rowFromBottom <= texelIndex(v1, height);
       ++rowFromBottom) {
    const double overlapV = std::min(v1, static_cast<double>(rowFromBottom + 1) / height) -
                            std::max(v0, static_cast<double>(rowFromBottom) / height);
    if (overlapV <= 0.0)
      continue;
    for (int column = texelIndex(u0, width); column <= texelIndex(u1, width); ++column) {
      const double overlapU = std::min(u1, static_cast<double>(column + 1) / width) -
                              std::max(u0, static_cast<double>(column) / width);
      if (overlapU <= 0.0)
        continue;
      const double weight = overlapU * overlapV;
      weightedSum += weight * glm::dvec3(texture.at(column, height - 1 - rowFromBottom));
      weightTotal += weight;
    }
  }
  if (weightTotal <= 0.0)
    return glm::vec3(texture.at(texelIndex(u0, width), height - 1 - texelIndex(v0, height)));
  return glm::vec3(weightedSum / weightTotal);
}

std::vector<Vpl> makeVpls(const QuadLight& light, glm::vec3 emission, const Image* texture,
                          int cellsPerSide) {
  std::vector<Vpl> vpls;
  if (cellsPerSide <= 0)
    return vpls;
  const auto count = static_cast<std::size_t>(cellsPerSide) * cellsPerSide;
  vpls.reserve(count);
  const auto gridLine = [cellsPerSide](int index) {
    return static_cast<float>(index) / static_cast<float>(cellsPerSide);
  };
  for (int j = 0; j < cellsPerSide; ++j) {
    for (int i = 0; i < cellsPerSide; ++i) {
      const glm::vec2 uvMin(gridLine(i), gridLine(j));
      const glm::vec2 uvMax(gridLine(i + 1), gridLine(j + 1));
      Vpl vpl;
      vpl.position = light.pointAt(0.5f * (uvMin + uvMax));
      vpl.normal = light.normal;
      vpl.radiance =
          texture != nullptr ? emission * textureCellMean(*texture, uvMin, uvMax) : emission;
      vpl.area = light.area / static_cast<float>(count);
      vpls.push_back(vpl);
    }
  }
  return vpls;
}

}  // namespace penumbra
