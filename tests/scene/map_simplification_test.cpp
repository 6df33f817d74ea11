// The reflective shadow maps' simplified meshes (simplifyForMaps, FrameGeometry::mapTriangles).
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "emitter_shapes.h"
#include "scene/model.h"
#include "scene/scene.h"
#include "test_files.h"

namespace penumbra {
namespace {

// A sphere of 261,120 triangles (far smaller than 1% of its size) in a red material, a sphere of
// 224 beside it in the default one.
constexpr std::string_view kSpheresScene = R"(material red
  dif 1 0 0
end
camera cam
  pos 0 0 8
  at 0 0 0
end
object fine.ply
  mat red
end
object coarse.obj
  translate 3 0 0
end
)";

Scene loadSpheres() {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "fine.ply", test::sphereBinaryPly(1.0, 256, 512));
  test::writeFile(directory, "coarse.obj", test::sphereObj(1.0, 8, 16));
  return loadScene(parseSceneFile(test::writeFile(directory, "spheres.scene", kSpheresScene)));
}

double areaOf(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles) {
  double area = 0.0;
  for (const glm::uvec3& t : triangles) {
    area += 0.5 * glm::length(glm::cross(glm::dvec3(positions[t.y] - positions[t.x]),
                                         glm::dvec3(positions[t.z] - positions[t.x])));
  }
  return area;
}

TEST(MapSimplification, AFineMeshKeepsItsSurfaceWithFarFewerTriangles) {
  const Scene scene = loadSpheres();
  const Mesh& fine = scene.objects[0].model.meshes.at(0);
  ASSERT_EQ(fine.triangles.size(), 261120u);
  ASSERT_FALSE(fine.mapTriangles.empty());
  std::printf("map triangles of the fine sphere: %zu\n", fine.mapTriangles.size());
  // Measured 71,476: about two triangles to a cell of the simplifier's grid, 1% of the sphere's
  // extent, of which its surface crosses about 31,000. A third fails a grid half as coarse.
  EXPECT_LT(fine.mapTriangles.size(), fine.triangles.size() / 3);
  for (const glm::uvec3& triangle : fine.mapTriangles)
    EXPECT_TRUE(glm::all(
        glm::lessThan(triangle, glm::uvec3(static_cast<unsigned>(fine.positions.size())))));
  // Its corners are the sphere's own vertices. Measured 0.36% more area than the fine sphere's
  // (the simplifier leaves some triangles overlapping); a hole (a lost cap, a missing band)
  // or a fold would take several per cent.
  const double fineArea = areaOf(fine.positions, fine.triangles);
  const double mapArea = areaOf(fine.positions, fine.mapTriangles);
  EXPECT_NEAR(mapArea / fineArea, 1.0, 0.01);
}

TEST(MapSimplification, ACoarseMeshKeepsItsOwnTriangles) {
  const Scene scene = loadSpheres();
  EXPECT_TRUE(scene.objects[1].model.meshes.at(0).mapTriangles.empty());
}

// Each batch's map triangles are its meshes' (simplified or their own), over the frame's vertices
// of those meshes; the coarse sphere's are its triangles exactly.
TEST(MapSimplification, EachBatchDrawsItsOwnMeshesInTheMaps) {
  const Scene scene = loadSpheres();
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  const auto fineVertices =
      static_cast<std::uint32_t>(scene.objects[0].model.meshes[0].positions.size());
  std::size_t mapTriangles = 0;
  ASSERT_EQ(geometry.batches.size(), 2u);
  for (const FrameGeometry::Batch& batch : geometry.batches) {
    const bool fineBatch = batch.material == scene.objects[0].meshMaterial[0];
    const std::uint32_t firstVertex = fineBatch ? 0 : fineVertices;
    const std::uint32_t endVertex =
        fineBatch ? fineVertices : static_cast<std::uint32_t>(geometry.positions.size());
    for (std::uint32_t t = batch.firstMapTriangle;
         t < batch.firstMapTriangle + batch.mapTriangleCount; ++t) {
      EXPECT_TRUE(
          glm::all(glm::greaterThanEqual(geometry.mapTriangles[t], glm::uvec3(firstVertex))));
      EXPECT_TRUE(glm::all(glm::lessThan(geometry.mapTriangles[t], glm::uvec3(endVertex))));
    }
    const auto begin = geometry.mapTriangles.begin() + batch.firstMapTriangle;
    if (fineBatch) {
      EXPECT_EQ(batch.mapTriangleCount, scene.objects[0].model.meshes[0].mapTriangles.size());
    } else {
      EXPECT_EQ(std::vector<glm::uvec3>(begin, begin + batch.mapTriangleCount),
                std::vector<glm::uvec3>(
                    geometry.triangles.begin() + batch.firstTriangle,
                    geometry.triangles.begin() + batch.firstTriangle + batch.triangleCount));
    }
    mapTriangles += batch.mapTriangleCount;
  }
  EXPECT_EQ(mapTriangles, geometry.mapTriangles.size());
}

}  // namespace
}  // namespace penumbra
