#include "scene/mesh_light.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/transform.h"

namespace penumbra {

namespace {

constexpr float kPi = 3.14159265358979f;

// Texture samples per side of a footprint piece: k^2 equal sub-triangles, each read at its
// centroid, give the piece's mean texture value.
constexpr int kTextureSamplesPerSide = 4;

glm::vec3 centroid(const EmitterTriangle& triangle) {
  return (triangle.positions[0] + triangle.positions[1] + triangle.positions[2]) / 3.0f;
}

EmitterTriangle makeTriangle(const std::array<glm::vec3, 3>& positions,
                             const std::array<glm::vec2, 3>& uvs, glm::vec3 normal) {
  EmitterTriangle triangle;
  triangle.positions = positions;
  triangle.uvs = uvs;
  triangle.normal = normal;
  triangle.area =
      0.5f * glm::length(glm::cross(positions[1] - positions[0], positions[2] - positions[0]));
  return triangle;
}

// The point at barycentric weights (w1, w2) of the second and third corners.
template <class T>
T interpolate(const std::array<T, 3>& corners, float w1, float w2) {
  return (1.0f - w1 - w2) * corners[0] + w1 * corners[1] + w2 * corners[2];
}

// Mean texture value over a triangle: the centroids of its k^2 equal sub-triangles.
glm::dvec3 textureMean(const Image& texture, const EmitterTriangle& triangle) {
  constexpr int k = kTextureSamplesPerSide;
  glm::dvec3 sum(0.0);
  for (int row = 0; row < k; ++row) {
    for (int column = 0; column + row < k; ++column) {
      const auto at = [&](float a, float b) {
        const glm::vec2 uv = interpolate(triangle.uvs, a / k, b / k);
        return glm::dvec3(textureCellMean(texture, uv, uv));
      };
      const auto c = static_cast<float>(column);
      const auto r = static_cast<float>(row);
      sum += at(c + 1.0f / 3.0f, r + 1.0f / 3.0f);  // upright sub-triangle
      if (column + row + 1 < k)
        sum += at(c + 2.0f / 3.0f, r + 2.0f / 3.0f);  // inverted sub-triangle
    }
  }
  return sum / static_cast<double>(k * k);
}

// The corner that starts the triangle's longest edge (corner, corner + 1).
int longestEdgeStart(const EmitterTriangle& triangle) {
  int longest = 0;
  float longestLength = -1.0f;
  for (int edge = 0; edge < 3; ++edge) {
    const float length = glm::length(triangle.positions[(edge + 1) % 3] - triangle.positions[edge]);
    if (length > longestLength) {
      longestLength = length;
      longest = edge;
    }
  }
  return longest;
}

// Cuts a triangle across its edge (a, b = a + 1) at a + t (b - a): the first piece, holding a,
// has fraction t of the area, exactly.
std::array<EmitterTriangle, 2> cutTriangle(const EmitterTriangle& triangle, int a, float t) {
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  const auto& p = triangle.positions;
  const auto& uv = triangle.uvs;
  const glm::vec3 cutPoint = glm::mix(p[a], p[b], t);
  const glm::vec2 cutUv = glm::mix(uv[a], uv[b], t);
  return {makeTriangle({p[a], cutPoint, p[c]}, {uv[a], cutUv, uv[c]}, triangle.normal),
          makeTriangle({cutPoint, p[b], p[c]}, {cutUv, uv[b], uv[c]}, triangle.normal)};
}

double totalArea(const std::vector<EmitterTriangle>& pieces) {
  double area = 0.0;
  for (const EmitterTriangle& piece : pieces)
    area += piece.area;
  return area;
}

Vpl cellVpl(const std::vector<EmitterTriangle>& cell, glm::vec3 emission, const Image* texture) {
  const double area = totalArea(cell);
  glm::dvec3 weightedCentroid(0.0);
  glm::dvec3 weightedNormal(0.0);
  glm::dvec3 weightedTexture(0.0);
  for (const EmitterTriangle& piece : cell) {
    weightedCentroid += static_cast<double>(piece.area) * glm::dvec3(centroid(piece));
    weightedNormal += static_cast<double>(piece.area) * glm::dvec3(piece.normal);
    if (texture != nullptr)
      weightedTexture += static_cast<double>(piece.area) * textureMean(*texture, piece);
  }
  const glm::vec3 cellCentroid(weightedCentroid / area);
  // The piece nearest the cell's centroid: a point on the surface even where the cell is curved.
  const auto nearest = std::min_element(
      cell.begin(), cell.end(), [&](const EmitterTriangle& x, const EmitterTriangle& y) {
        return glm::length(centroid(x) - cellCentroid) < glm::length(centroid(y) - cellCentroid);
      });
  Vpl vpl;
  vpl.position = centroid(*nearest);
  vpl.normal = glm::length(weightedNormal) > 0.0 ? glm::vec3(glm::normalize(weightedNormal))
                                                 : nearest->normal;
  vpl.area = static_cast<float>(area);
  vpl.radiance = texture != nullptr ? emission * glm::vec3(weightedTexture / area) : emission;
  return vpl;
}

void splitCells(std::vector<EmitterTriangle> pieces, int count, glm::vec3 emission,
                const Image* texture, std::vector<Vpl>& out) {
  if (count == 1) {
    out.push_back(cellVpl(pieces, emission, texture));
    return;
  }
  const int leftCount = count / 2;
  const double target = totalArea(pieces) * leftCount / count;

  glm::vec3 low(std::numeric_limits<float>::infinity());
  glm::vec3 high(-std::numeric_limits<float>::infinity());
  for (const EmitterTriangle& piece : pieces) {
    for (const glm::vec3& corner : piece.positions) {
      low = glm::min(low, corner);
      high = glm::max(high, corner);
    }
  }
  const glm::vec3 extent = high - low;
  const int axis = extent.x >= std::max(extent.y, extent.z) ? 0 : (extent.y >= extent.z ? 1 : 2);
  std::stable_sort(pieces.begin(), pieces.end(),
                   [axis](const EmitterTriangle& x, const EmitterTriangle& y) {
                     return centroid(x)[axis] < centroid(y)[axis];
                   });

  std::vector<EmitterTriangle> left;
  std::vector<EmitterTriangle> right;
  double before = 0.0;
  for (const EmitterTriangle& piece : pieces) {
    const double after = before + piece.area;
    if (after <= target) {
      left.push_back(piece);
    } else if (before >= target) {
      right.push_back(piece);
    } else {
      // The straddling piece: the part of it on the low side of the axis goes left.
      const auto fraction = static_cast<float>((target - before) / piece.area);
      const int a = longestEdgeStart(piece);
      const bool aOnLowSide = piece.positions[a][axis] <= piece.positions[(a + 1) % 3][axis];
      const std::array<EmitterTriangle, 2> parts =
          cutTriangle(piece, a, aOnLowSide ? fraction : 1.0f - fraction);
      const EmitterTriangle& lowPart = parts[aOnLowSide ? 0 : 1];
      const EmitterTriangle& highPart = parts[aOnLowSide ? 1 : 0];
      if (lowPart.area > 0.0f)
        left.push_back(lowPart);
      if (highPart.area > 0.0f)
        right.push_back(highPart);
    }
    before = after;
  }
  // Rounding can leave a side without a piece; it then shares its neighbour's pieces' places.
  if (left.empty())
    left.push_back(right.front());
  if (right.empty())
    right.push_back(left.back());
  splitCells(std::move(left), leftCount, emission, texture, out);
  splitCells(std::move(right), count - leftCount, emission, texture, out);
}

}  // namespace

MeshLightGeometry meshLightGeometry(const Scene& scene, const Light& light, int frame) {
  MeshLightGeometry geometry;
  const SceneObject& object = scene.objects[static_cast<std::size_t>(light.object)];
  const glm::mat4 worldFromModel = worldFromObject(object.desc, frame);
  const glm::mat3 normalTransform = normalMatrix(worldFromModel);
  glm::vec3 low(std::numeric_limits<float>::infinity());
  glm::vec3 high(-std::numeric_limits<float>::infinity());
  glm::dvec3 normalSum(0.0);
  for (const std::size_t m : light.meshes) {
    const Mesh& mesh = object.model.meshes[m];
    for (const glm::uvec3& t : mesh.triangles) {
      std::array<glm::vec3, 3> positions;
      std::array<glm::vec2, 3> uvs;
      glm::vec3 vertexNormals(0.0f);
      for (int corner = 0; corner < 3; ++corner) {
        positions[corner] = glm::vec3(worldFromModel * glm::vec4(mesh.positions[t[corner]], 1.0f));
        uvs[corner] = mesh.uvs[t[corner]];
        vertexNormals += normalTransform * mesh.normals[t[corner]];
      }
      const glm::vec3 face = glm::cross(positions[1] - positions[0], positions[2] - positions[0]);
      if (!(glm::length(face) > 0.0f))
        continue;
      glm::vec3 normal = glm::normalize(face);
      if (glm::dot(normal, vertexNormals) < 0.0f)
        normal = -normal;
      const EmitterTriangle triangle = makeTriangle(positions, uvs, normal);
      geometry.triangles.push_back(triangle);
      geometry.area += triangle.area;
      normalSum += static_cast<double>(triangle.area) * glm::dvec3(normal);
      for (const glm::vec3& p : positions) {
        low = glm::min(low, p);
        high = glm::max(high, p);
      }
    }
  }
  if (!geometry.triangles.empty()) {
    geometry.boundsMin = low;
    geometry.boundsMax = high;
  }
  // A closed mesh's normals cancel (up to rounding); it has no main direction.
  if (glm::length(normalSum) > 1e-6 * geometry.area)
    geometry.meanNormal = glm::vec3(glm::normalize(normalSum));
  return geometry;
}

std::vector<Vpl> makeMeshVpls(const MeshLightGeometry& geometry, glm::vec3 emission,
                              const Image* texture, bool twoSided, int count) {
  std::vector<Vpl> vpls;
  if (count <= 0 || geometry.triangles.empty())
    return vpls;
  const bool pairs = twoSided && count >= 2;
  const int cells = pairs ? count / 2 : count;
  std::vector<Vpl> cellVpls;
  splitCells(geometry.triangles, cells, emission, texture, cellVpls);
  for (const Vpl& vpl : cellVpls) {
    vpls.push_back(vpl);
    if (pairs) {
      Vpl back = vpl;
      back.normal = -vpl.normal;
      vpls.push_back(back);
    }
  }
  if (static_cast<int>(vpls.size()) < count) {
    Vpl unused = vpls.front();
    unused.area = 0.0f;
    unused.radiance = glm::vec3(0.0f);
    vpls.push_back(unused);
  }
  return vpls;
}

glm::vec3 emittedPower(const std::vector<Vpl>& vpls) {
  glm::dvec3 power(0.0);
  for (const Vpl& vpl : vpls)
    power += kPi * static_cast<double>(vpl.area) * glm::dvec3(vpl.radiance);
  return glm::vec3(power);
}

MeshLightSampler::MeshLightSampler(const MeshLightGeometry& geometry) : geometry_(&geometry) {
  cumulative_.reserve(geometry.triangles.size());
  for (const EmitterTriangle& triangle : geometry.triangles) {
    total_ += triangle.area;
    cumulative_.push_back(total_);
  }
}

SurfaceSample MeshLightSampler::sample(glm::vec2 u) const {
  const double target = static_cast<double>(u.x) * total_;
  const auto found = std::upper_bound(cumulative_.begin(), cumulative_.end(), target);
  const auto index = static_cast<std::size_t>(std::min<std::ptrdiff_t>(
      found - cumulative_.begin(), static_cast<std::ptrdiff_t>(cumulative_.size()) - 1));
  const EmitterTriangle& triangle = geometry_->triangles[index];
  const double start = index == 0 ? 0.0 : cumulative_[index - 1];
  const float within = std::clamp(static_cast<float>((target - start) / triangle.area), 0.0f, 1.0f);
  // Uniform in the triangle: sqrt warps the first coordinate so equal areas get equal measure.
  const float s = std::sqrt(within);
  const float w1 = s * (1.0f - u.y);
  const float w2 = s * u.y;
  return {interpolate(triangle.positions, w1, w2), triangle.normal,
          interpolate(triangle.uvs, w1, w2)};
}

}  // namespace penumbra
