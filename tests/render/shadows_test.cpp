// Area-light shadows through the voxel grid: voxelization, known lit and shadowed points, the
// penumbra's geometry and hue, moving shadows, the occluder outside the view, and agreement of
// the voxel visibility with Embree's exact visibility for the same VPLs.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "reference/ray_scene.h"
#include "render/debug_views.h"
#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "render/voxel_queries.h"
#include "scene/transform.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra {
namespace {

std::string quoted(const std::filesystem::path& path) {
  return "\"" + path.string() + "\"";
}

std::string cubeObject() {
  return quoted(test::sourceDirectory() / "scenes/assets/cube.obj");
}

std::vector<std::uint32_t> readWords(const VoxelGrid& grid) {
  return readBuffer<std::uint32_t>(grid.words.id(), 0, grid.wordCount);
}

bool bitAt(const std::vector<std::uint32_t>& words, glm::ivec3 resolution, int axis,
           glm::ivec3 voxel) {
  const auto [word, bit] = test::voxelLocation(resolution, axis, voxel);
  return (words[word] >> bit & 1u) != 0u;
}

// The voxels set in the columns along z; a failure (and the count so far) where the columns along
// x or y differ from them.
std::size_t countOccupiedInEveryCopy(const std::vector<std::uint32_t>& words,
                                     glm::ivec3 resolution) {
  std::size_t occupied = 0;
  for (int z = 0; z < resolution.z; ++z)
    for (int y = 0; y < resolution.y; ++y)
      for (int x = 0; x < resolution.x; ++x) {
        const glm::ivec3 voxel(x, y, z);
        const bool set = bitAt(words, resolution, 2, voxel);
        occupied += set ? 1 : 0;
        if (bitAt(words, resolution, 0, voxel) != set ||
            bitAt(words, resolution, 1, voxel) != set) {
          ADD_FAILURE() << "the copies differ at " << x << "," << y << "," << z;
          return occupied;
        }
      }
  return occupied;
}

// A unit cube at the origin under a light: only the cube and the light quad mark voxels.
const std::string kCubeUnderLight =
    "material glow\n  emit 1 1 1\nend\n"
    "area_light square\n"
    "  pos1 -0.5 1.5 -0.5\n  pos2 0.5 1.5 -0.5\n  pos3 0.5 1.5 0.5\n  pos4 -0.5 1.5 0.5\n"
    "  at 0 0 0\n  mat glow\nend\n"
    "camera c\n  pos 0.5 0.8 3\n  at 0 0 0\n  screen_size 32 32\nend\n";

RenderSettings voxelOnlySettings(VoxelSettings::Grid grid, VoxelSettings::Fill fill) {
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 1;
  settings.shadows.voxels.grid = grid;
  settings.shadows.voxels.fill = fill;
  // The same count along every axis, which the tests below index by.
  settings.shadows.voxels.shape = VoxelSettings::Shape::Equal;
  settings.shadows.voxels.resolution = 32;
  settings.shadows.voxels.depthSlices = 64;
  settings.shadows.voxels.traversal = grid == VoxelSettings::Grid::World
                                          ? VoxelSettings::Traversal::Dda
                                          : VoxelSettings::Traversal::Uniform;
  return settings;
}

// A world grid of `resolution` voxels per axis over the surfaces.
RenderSettings surfaceGridSettings(int resolution) {
  RenderSettings settings =
      voxelOnlySettings(VoxelSettings::Grid::World, VoxelSettings::Fill::Surface);
  settings.shadows.voxels.resolution = resolution;
  return settings;
}

Scene cubeUnderLight() {
  return test::loadSceneText(test::scratchDirectory(),
                             kCubeUnderLight + "object " + cubeObject() + "\nend\n");
}

TEST(Voxelization, SolidFillFillsAClosedCubeAndSurfaceFillOnlyItsShell) {
  Scene scene = cubeUnderLight();
  Renderer renderer(scene, scene.camera.size);
  for (const auto fill : {VoxelSettings::Fill::Solid, VoxelSettings::Fill::Surface}) {
    const bool solid = fill == VoxelSettings::Fill::Solid;
    renderer.render(0, voxelOnlySettings(VoxelSettings::Grid::World, fill));
    const VoxelGrid& grid = renderer.voxelGrid();
    const glm::ivec3 resolution(grid.description.resolution);
    const glm::vec3 low(grid.description.boundsMin);
    const glm::vec3 size(grid.description.voxelSize);
    const std::vector<std::uint32_t> words = readWords(grid);
    // The columns, then the occupancy pyramid and the boxes inside the voxels (their own tests
    // below).
    ASSERT_GT(test::boxWordCount(grid.description), 0u);
    ASSERT_EQ(words.size(), test::voxelWordCount(resolution, true) +
                                test::occupancyWordCount(grid.description) +
                                test::boxWordCount(grid.description));
    int inside = 0;
    int outside = 0;
    for (int z = 0; z < resolution.z; ++z) {
      for (int y = 0; y < resolution.y; ++y) {
        for (int x = 0; x < resolution.x; ++x) {
          const glm::ivec3 voxel(x, y, z);
          const bool occupied = bitAt(words, resolution, 2, voxel);
          // The columns along x and y hold the same voxels as those along z.
          ASSERT_EQ(bitAt(words, resolution, 0, voxel), occupied) << x << "," << y << "," << z;
          ASSERT_EQ(bitAt(words, resolution, 1, voxel), occupied) << x << "," << y << "," << z;
          // Centres more than a voxel inside the cube's faces, or outside them (below the light
          // quad, which marks voxels of its own): the surface's voxels lie between the two.
          const glm::vec3 centre = low + (glm::vec3(voxel) + 0.5f) * size;
          const glm::vec3 depthInside = glm::vec3(0.5f) - glm::abs(centre);
          if (glm::all(glm::greaterThan(depthInside, size))) {
            ++inside;
            EXPECT_EQ(occupied, solid) << "inside at " << x << "," << y << "," << z;
          } else if (glm::any(glm::lessThan(depthInside, -size)) && centre.y < 1.3f) {
            ++outside;
            EXPECT_FALSE(occupied) << "outside at " << x << "," << y << "," << z;
          }
        }
      }
    }
    EXPECT_GT(inside, 1000);
    EXPECT_GT(outside, 1000);
  }
}

// A point on a face of the unit cube centred on the origin: 48 x 48 of them on each face.
struct CubeFacePoint {
  int face;      // 0 to 5: -x, +x, -y, +y, -z, +z
  int axis;      // the face's normal axis
  glm::vec3 at;  // in the cube's own coordinates
};

std::vector<CubeFacePoint> cubeFacePoints() {
  std::vector<CubeFacePoint> points;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    for (int i = 0; i < 48; ++i) {
      for (int j = 0; j < 48; ++j) {
        glm::vec3 at;
        at[axis] = face % 2 == 0 ? -0.5f : 0.5f;
        at[(axis + 1) % 3] = -0.5f + (static_cast<float>(i) + 0.5f) / 48.0f;
        at[(axis + 2) % 3] = -0.5f + (static_cast<float>(j) + 0.5f) / 48.0f;
        points.push_back({face, axis, at});
      }
    }
  }
  return points;
}

// The world grid of a scene voxelized as surfaces, its words read back.
struct SurfaceGrid {
  gpu::GpuVoxelGrid description;
  std::vector<std::uint32_t> words;

  glm::vec3 gridCoordinates(glm::vec3 world) const {
    return (world - glm::vec3(description.boundsMin)) / glm::vec3(description.voxelSize);
  }
};

SurfaceGrid voxelizeSurfaces(Scene scene) {
  Renderer renderer(scene, scene.camera.size);
  renderer.render(0, voxelOnlySettings(VoxelSettings::Grid::World, VoxelSettings::Fill::Surface));
  return {renderer.voxelGrid().description, readWords(renderer.voxelGrid())};
}

std::string describe(glm::vec3 point) {
  return std::to_string(point.x) + "," + std::to_string(point.y) + "," + std::to_string(point.z);
}

// The boxes inside the voxels (GpuVoxelGrid::occupancy) hold every point of the surfaces: points
// on the cube's six faces lie inside their voxel's box (grown by the traversal's margin, a
// thousandth of a voxel), or the traversal would pass the cube there. And they hold a face
// parallel to two axes within two slices (a slice is a 32nd of a voxel) along its normal, where
// it is the only surface in its voxel (more than a voxel from the face's edges), which is what
// keeps shadows from growing by up to a voxel.
TEST(Voxelization, BoxesInsideTheVoxelsHoldTheSurfacesAndNoMoreOfAFlatFace) {
  const SurfaceGrid grid = voxelizeSurfaces(cubeUnderLight());
  const glm::ivec3 resolution(grid.description.resolution);
  const glm::vec3 size(grid.description.voxelSize);
  int tight = 0;
  for (const CubeFacePoint& point : cubeFacePoints()) {
    const int axis = point.axis;
    const glm::vec3 inGrid = grid.gridCoordinates(point.at);
    const glm::ivec3 voxel(glm::floor(inGrid));
    ASSERT_TRUE(bitAt(grid.words, resolution, 2, voxel)) << describe(point.at);
    const test::VoxelContent content = test::voxelContent(grid.words, grid.description, voxel);
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(inGrid, content.low - 1e-3f)) &&
                glm::all(glm::lessThanEqual(inGrid, content.high + 1e-3f)))
        << "point " << describe(point.at) << " outside its box";
    const glm::vec3 fromEdges = glm::vec3(0.5f) - glm::abs(point.at);
    const bool onlyThisFace = fromEdges[(axis + 1) % 3] > size[(axis + 1) % 3] + size[axis] &&
                              fromEdges[(axis + 2) % 3] > size[(axis + 2) % 3] + size[axis];
    if (onlyThisFace) {
      ++tight;
      EXPECT_LE(content.high[axis] - content.low[axis], 2.0f / gpu::kVoxelBoxSlices)
          << "face " << point.face << " at " << describe(point.at);
    }
  }
  EXPECT_GT(tight, 6 * 1000);
}

// The slabs inside the voxels (GpuVoxelGrid::occupancy) of a cube turned about an oblique axis,
// whose faces are parallel to no axis, so that their boxes fill much of each voxel: points on the
// six faces lie inside their voxel's box and both its slabs (grown by the traversal's margin), or
// the traversal would pass the cube there. Where a face is the only surface in its voxel (farther
// than a voxel's diagonal from its edges), both slabs hold it within two slices (a slice is a
// 16th of the voxel's extent along the slab's normal): the box alone would hold it within the
// whole voxel, and its shadow would grow by up to a voxel.
TEST(Voxelization, SlabsHoldATurnedCubesFacesWithinTwoSlices) {
  const float angle = 35.0f;
  const glm::vec3 axis(1.0f, 2.0f, 0.5f);
  const SurfaceGrid grid = voxelizeSurfaces(test::loadSceneText(
      test::scratchDirectory(), kCubeUnderLight + "object " + cubeObject() + "\n  rotate " +
                                    std::to_string(angle) + " 1 2 0.5\nend\n"));
  const glm::mat4 turn = rotationMatrix(angle, axis);
  const float voxelDiagonal = glm::length(glm::vec3(grid.description.voxelSize));
  int tight = 0;
  for (const CubeFacePoint& point : cubeFacePoints()) {
    const glm::vec3 world(turn * glm::vec4(point.at, 1.0f));
    const glm::vec3 inGrid = grid.gridCoordinates(world);
    const glm::ivec3 voxel(glm::floor(inGrid));
    const test::VoxelContent content = test::voxelContent(grid.words, grid.description, voxel);
    ASSERT_EQ(content.slabs.size(), 2u) << "no slabs at " << describe(world);
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(inGrid, content.low - 1e-3f)) &&
                glm::all(glm::lessThanEqual(inGrid, content.high + 1e-3f)))
        << "point " << describe(world) << " outside its box";
    const glm::vec3 fromEdges = glm::vec3(0.5f) - glm::abs(point.at);
    const bool onlyThisFace = fromEdges[(point.axis + 1) % 3] > voxelDiagonal &&
                              fromEdges[(point.axis + 2) % 3] > voxelDiagonal;
    tight += onlyThisFace ? 1 : 0;
    for (const test::VoxelSlab& slab : content.slabs) {
      const float height = glm::dot(slab.normal, inGrid - (glm::vec3(voxel) + 0.5f));
      EXPECT_TRUE(height >= slab.low - 1e-3f && height <= slab.high + 1e-3f)
          << "point " << describe(world) << " outside a slab";
      const float slice =
          (std::abs(slab.normal.x) + std::abs(slab.normal.y) + std::abs(slab.normal.z)) /
          gpu::kVoxelPlaneSlices;
      if (onlyThisFace) {
        EXPECT_LE(slab.high - slab.low, 2.0f * slice + 1e-5f)
            << "face " << point.face << " at " << describe(world);
      }
    }
  }
  EXPECT_GT(tight, 6 * 500);
}

// A grid of 512 voxels per axis: the first size whose transposition into columns along x and y
// takes more work groups than one dispatch may have along x (512 x 512 x 16 words, 65536 groups of
// 64), which GL refused before the dispatch went on in rows. Every word of both copies is
// written, from the columns along z.
TEST(Voxelization, FineGridFillsEveryColumnOfEachCopy) {
  Scene scene = cubeUnderLight();
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings = surfaceGridSettings(512);
  renderer.render(0, settings);
  const VoxelGrid& grid = renderer.voxelGrid();
  const glm::ivec3 resolution(grid.description.resolution);
  ASSERT_EQ(resolution, glm::ivec3(512));
  const std::vector<std::uint32_t> words = readWords(grid);
  const std::size_t occupied = countOccupiedInEveryCopy(words, resolution);
  // The cube's six faces and the light's quad, each at least a layer of voxels.
  EXPECT_GT(occupied, 6u * 200 * 200);
}

// A grid of 40 voxels along x and y: the columns along x and y end 8 voxels into their second
// word, so the transposition's last tile of each row reads 8 columns along z and leaves the
// other 24 bits of its words clear. The solid fill sets every voxel inside the cube, so that
// its tiles hold set bits in every row and column.
TEST(Voxelization, TranspositionCopiesColumnsThatEndInsideAWord) {
  Scene scene = cubeUnderLight();
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings =
      voxelOnlySettings(VoxelSettings::Grid::World, VoxelSettings::Fill::Solid);
  settings.shadows.voxels.resolution = 40;
  renderer.render(0, settings);
  const VoxelGrid& grid = renderer.voxelGrid();
  const glm::ivec3 resolution(grid.description.resolution);
  // The z resolution is rounded up to whole words.
  ASSERT_EQ(resolution, glm::ivec3(40, 40, 64));
  const std::vector<std::uint32_t> words = readWords(grid);
  const std::size_t occupied = countOccupiedInEveryCopy(words, resolution);
  // The grid fits the scene's bounds on each axis, so the solid cube fills all of it but the
  // upper half along y, where the light is: about 40 x 20 x 64 voxels.
  EXPECT_GT(occupied, 40000u);
  // Bits past the 40th voxel of a column along x or y stay clear: those columns follow the block
  // along z, two words each, and their second words hold voxels 32 to 39 in bits 0 to 7.
  const std::size_t acrossBlocksStart = test::voxelWordCount(resolution, false);
  const std::size_t acrossBlocksEnd = test::voxelWordCount(resolution, true);
  for (std::size_t word = acrossBlocksStart + 1; word < acrossBlocksEnd; word += 2)
    ASSERT_EQ(words[word] >> 8, 0u) << "word " << word;
}

// Voxels of a world grid along `axis` that overlap [from, to] in world space.
int voxelsOverlapping(const gpu::GpuVoxelGrid& grid, int axis, float from, float to) {
  const float first = std::floor((from - grid.boundsMin[axis]) / grid.voxelSize[axis]);
  const float last = std::floor((to - grid.boundsMin[axis]) / grid.voxelSize[axis]);
  return static_cast<int>(last - first) + 1;
}

// A cubic grid over a box twice as tall as it is wide (the solid unit cube from y = -0.5 and the
// light quad at y = 1.5): as many voxels as 48^3, shared out in proportion to the sides, so about
// twice as many along y as along x and z, each copy of the columns in the layout of that shape.
TEST(Voxelization, CubicGridSharesItsVoxelsOutInProportionToTheScenesBox) {
  Scene scene = cubeUnderLight();
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings =
      voxelOnlySettings(VoxelSettings::Grid::World, VoxelSettings::Fill::Solid);
  settings.shadows.voxels.shape = VoxelSettings::Shape::Cubic;
  settings.shadows.voxels.resolution = 48;
  renderer.render(0, settings);
  const VoxelGrid& grid = renderer.voxelGrid();
  const glm::ivec3 resolution(grid.description.resolution);
  const glm::vec3 size(grid.description.voxelSize);
  // x and y each round a side over the cube root of the box's volume over 48^3 to whole voxels
  // (38.3 and 75.2 here); z takes the nearest whole word.
  EXPECT_EQ(resolution, glm::ivec3(38, 75, 32));
  EXPECT_NEAR(size.y / size.x, 1.0f, 0.02f);
  const std::vector<std::uint32_t> words = readWords(grid);
  ASSERT_EQ(words.size(), test::voxelWordCount(resolution, true) +
                              test::occupancyWordCount(grid.description) +
                              test::boxWordCount(grid.description));
  // Every voxel that overlaps the solid cube, in all three copies of the columns, and the light
  // quad's layer of one or two voxels above it.
  const int cube = voxelsOverlapping(grid.description, 0, -0.5f, 0.5f) *
                   voxelsOverlapping(grid.description, 1, -0.5f, 0.5f) *
                   voxelsOverlapping(grid.description, 2, -0.5f, 0.5f);
  const int lightLayer = voxelsOverlapping(grid.description, 0, -0.5f, 0.5f) *
                         voxelsOverlapping(grid.description, 2, -0.5f, 0.5f);
  const std::size_t occupied = countOccupiedInEveryCopy(words, resolution);
  EXPECT_GE(occupied, static_cast<std::size_t>(cube + lightLayer));
  EXPECT_LE(occupied, static_cast<std::size_t>(cube + 2 * lightLayer));
}

// The occupancy pyramid that the clear-light test descends (voxel_grid.glsl, cellBounds), against
// one computed here from the voxels: level 1 a bit per 2x2x2 cell (in columns along z), each level
// above the box of the occupied voxels of its cell, bounds rounded outwards to the level's unit.
TEST(Voxelization, OccupancyPyramidHoldsTheBoxOfEachCellsVoxels) {
  Scene scene = cubeUnderLight();
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings = surfaceGridSettings(40);
  // The pyramid is built for the hierarchy's clear-light test only.
  settings.mode = RenderMode::Hierarchical;
  renderer.render(0, settings);
  const gpu::GpuVoxelGrid& grid = renderer.voxelGrid().description;
  const glm::ivec3 resolution(grid.resolution);
  const std::vector<std::uint32_t> words = readWords(renderer.voxelGrid());
  // 40 voxels (z: 64) halve to 20, 10, 5, 3 (z: 32, 16, 8, 4): the coarsest has at most 4 per axis.
  ASSERT_EQ(grid.occupancy.x, 4);
  EXPECT_EQ(glm::ivec3(grid.occupancyLevels[3]), glm::ivec3(3, 3, 4));

  // Each level's boxes, computed from the voxels: low and high (exclusive) per cell.
  struct Box {
    glm::ivec3 low{std::numeric_limits<int>::max()};
    glm::ivec3 high{-1};
  };
  std::size_t occupiedCells = 0;
  for (int level = 1; level <= grid.occupancy.x; ++level) {
    const glm::ivec4 cells = grid.occupancyLevels[static_cast<std::size_t>(level - 1)];
    std::vector<Box> boxes(static_cast<std::size_t>(cells.x * cells.y * cells.z));
    for (int z = 0; z < resolution.z; ++z)
      for (int y = 0; y < resolution.y; ++y)
        for (int x = 0; x < resolution.x; ++x) {
          const glm::ivec3 voxel(x, y, z);
          if (!bitAt(words, resolution, 2, voxel))
            continue;
          const glm::ivec3 cell = voxel >> level;
          Box& box =
              boxes[static_cast<std::size_t>((cell.z * cells.y + cell.y) * cells.x + cell.x)];
          box.low = glm::min(box.low, voxel);
          box.high = glm::max(box.high, voxel + 1);
        }
    const int unit = 1 << std::max(level - 5, 0);
    for (int index = 0; index < cells.x * cells.y * cells.z; ++index) {
      const Box& box = boxes[static_cast<std::size_t>(index)];
      const bool occupied = box.high.x >= 0;
      occupiedCells += occupied ? 1 : 0;
      const glm::ivec3 cell(index % cells.x, (index / cells.x) % cells.y,
                            index / (cells.x * cells.y));
      if (level == 1) {
        // Bits in columns along z, as the voxels'.
        const int columnWords = (cells.z + 31) / 32;
        const std::uint32_t word = words[static_cast<std::size_t>(
            cells.w + (cell.y * cells.x + cell.x) * columnWords + cell.z / 32)];
        EXPECT_EQ((word >> (cell.z % 32) & 1u) != 0u, occupied) << "level 1 cell " << index;
        continue;
      }
      const std::uint32_t word = words[static_cast<std::size_t>(cells.w + index)];
      if (!occupied) {
        EXPECT_EQ(word, gpu::kEmptyCell) << "level " << level << " cell " << index;
        continue;
      }
      const glm::ivec3 origin = cell << level;
      const glm::ivec3 first = (box.low - origin) / unit;
      const glm::ivec3 last = (box.high - origin + unit - 1) / unit - 1;
      const std::uint32_t expected = static_cast<std::uint32_t>(
          first.x | first.y << 5 | first.z << 10 | last.x << 15 | last.y << 20 | last.z << 25);
      EXPECT_EQ(word, expected) << "level " << level << " cell " << index;
    }
  }
  EXPECT_GT(occupiedCells, 100u);
}

TEST(Voxelization, SliceViewShowsTheFilledCube) {
  Scene scene = cubeUnderLight();
  Renderer renderer(scene, scene.camera.size);
  renderer.render(0, voxelOnlySettings(VoxelSettings::Grid::World, VoxelSettings::Fill::Solid));
  const gpu::GpuVoxelGrid& grid = renderer.voxelGrid().description;
  // The middle slice along z cuts the cube's [-0.5, 0.5] square in x and y.
  const RenderSettings settings =
      voxelOnlySettings(VoxelSettings::Grid::World, VoxelSettings::Fill::Solid);
  const Image slice = debugView(renderer, "voxels-16", settings);
  ASSERT_EQ(slice.width, renderer.gbuffer().size.x);
  int white = 0;
  for (int row = 0; row < slice.height; ++row) {
    for (int column = 0; column < slice.width; ++column) {
      // The view stretches the grid over the image, row 0 at the top (highest y).
      const glm::vec2 world =
          glm::vec2(grid.boundsMin) +
          glm::vec2((static_cast<float>(column) + 0.5f) / static_cast<float>(slice.width),
                    1.0f - (static_cast<float>(row) + 0.5f) / static_cast<float>(slice.height)) *
              glm::vec2(grid.resolution) * glm::vec2(grid.voxelSize);
      const bool occupied = slice.at(column, row).r == 1.0f;
      white += occupied ? 1 : 0;
      // A voxel (0.06 in y, 0.03 in x) of margin around the cube's outline either way.
      if (glm::all(glm::lessThan(glm::abs(world), glm::vec2(0.42f)))) {
        EXPECT_TRUE(occupied) << column << "," << row;
      } else if (glm::any(glm::greaterThan(glm::abs(world), glm::vec2(0.58f))) && world.y < 1.3f) {
        EXPECT_FALSE(occupied) << column << "," << row;
      }
    }
  }
  EXPECT_GT(white, 100);
  const std::vector<std::string> names = debugViewNames(renderer);
  const std::string lastSlice = "voxels-" + std::to_string(grid.resolution.z - 1);
  EXPECT_NE(std::find(names.begin(), names.end(), lastSlice), names.end());
  EXPECT_THROW(debugView(renderer, "voxels-" + std::to_string(grid.resolution.z), settings),
               RenderError);
  // The frame was naive: no visibility masks, no pyramid.
  EXPECT_THROW(debugView(renderer, "visible-vpls", settings), RenderError);
  EXPECT_THROW(debugView(renderer, "levels", settings), RenderError);
}

// Pixels (row 0 at the top, as readRadiance) whose surface point lies nearest each world point.
std::vector<glm::ivec2> nearestPixels(const Renderer& renderer,
                                      const std::vector<glm::vec3>& points) {
  const glm::ivec2 size = renderer.gbuffer().size;
  const Image positions =
      readTexture(renderer.gbuffer().positionDepth.id(), size, RowOrder::TopFirst);
  const Image normals = readTexture(renderer.gbuffer().normalKind.id(), size, RowOrder::TopFirst);
  std::vector<glm::ivec2> pixels;
  for (const glm::vec3 point : points) {
    float nearest = 1e30f;
    glm::ivec2 found(-1);
    for (int y = 0; y < size.y; ++y) {
      for (int x = 0; x < size.x; ++x) {
        if (static_cast<int>(normals.at(x, y).w) != gpu::kPixelSurface)
          continue;
        const float distance = glm::length(glm::vec3(positions.at(x, y)) - point);
        if (distance < nearest) {
          nearest = distance;
          found = {x, y};
        }
      }
    }
    pixels.push_back(found);
  }
  return pixels;
}

Image render(Renderer& renderer, RenderSettings settings, RenderMode mode, int frame = 0) {
  settings.mode = mode;
  renderer.render(frame, settings);
  return renderer.readRadiance();
}

// A 4 x 4 floor, a 1 x 1 light at height 2 facing down (material `light`, defined by the
// caller's `materials`), and a square slab 0.04 thick and `side` wide centred at `height`, with
// object keys `slabKeys`. The camera looks along -z at the floor under the slab.
std::string slabScene(float height, float side, const std::string& materials,
                      const std::string& slabKeys = "") {
  const std::string floor = quoted(test::sourceDirectory() / "scenes/assets/floor.obj");
  const std::string slab = "  translate 0 " + std::to_string(height) + " 0\n  scale " +
                           std::to_string(side) + " 0.04 " + std::to_string(side) + "\n";
  return materials + "material grey\n  dif 0.8 0.8 0.8\nend\n" +
         "area_light overhead\n"
         "  pos1 -0.5 2 0.5\n  pos2 0.5 2 0.5\n  pos3 0.5 2 -0.5\n  pos4 -0.5 2 -0.5\n"
         "  at 0 0 0\n  mat light\nend\n"
         "camera side\n  pos 0 1.2 3.5\n  at 0 0 0\n  fovy 60\n  screen_size 128 128\nend\n" +
         "object " + floor + "\n  scale 4\n  mat grey\nend\n" + "object " + cubeObject() + "\n" +
         slabKeys + slab + "  mat grey\nend\n";
}

const std::string kWhiteLight = "material light\n  emit 10 10 10\nend\n";

// Floor points (x, 0, 0) for x from `from` to `to` in `count` steps.
std::vector<glm::vec3> floorLine(float from, float to, int count) {
  std::vector<glm::vec3> points;
  for (int i = 0; i < count; ++i)
    points.push_back(
        {from + (to - from) * static_cast<float>(i) / static_cast<float>(count - 1), 0.0f, 0.0f});
  return points;
}

// Shadowed over unshadowed radiance (red channel) at each pixel.
std::vector<float> litFractions(const Image& shadowed, const Image& unshadowed,
                                const std::vector<glm::ivec2>& pixels) {
  std::vector<float> fractions;
  for (const glm::ivec2 pixel : pixels)
    fractions.push_back(shadowed.at(pixel.x, pixel.y).r / unshadowed.at(pixel.x, pixel.y).r);
  return fractions;
}

TEST(Shadows, PointsUnderTheOccluderAreDarkAndPointsFarFromItAreFullyLit) {
  const auto directory = test::scratchDirectory();
  // A 1.2-wide slab at height 1: the floor is in full shadow for |x|, |z| < 0.7 and fully lit
  // beyond 1.7 (light 1 wide at height 2).
  Scene scene = test::loadSceneText(directory, slabScene(1.0f, 1.2f, kWhiteLight));
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.vplsPerLight = 64;
  for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    settings.shadows.enabled = false;
    const Image unshadowed = render(renderer, settings, mode);
    const std::vector<glm::ivec2> pixels = nearestPixels(
        renderer,
        {{0.0f, 0.0f, 0.0f}, {0.3f, 0.0f, 0.2f}, {-1.9f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f}});
    settings.shadows.enabled = true;
    const Image shadowed = render(renderer, settings, mode);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      const glm::vec3 found(shadowed.at(pixels[i].x, pixels[i].y));
      const glm::vec3 unblocked(unshadowed.at(pixels[i].x, pixels[i].y));
      ASSERT_GT(unblocked.r, 0.01f) << "point " << i << " must face the light";
      if (i < 2) {
        // Every VPL is blocked and nothing else lights the floor: exactly black.
        EXPECT_EQ(found, glm::vec3(0.0f)) << renderModeName(mode) << " point " << i;
      } else {
        // Every VPL is visible: the same sum as without shadows (the hierarchy gathers it from
        // the same texels, far from any change of visibility).
        EXPECT_EQ(found, unblocked) << renderModeName(mode) << " point " << i;
      }
    }
  }
}

// Where the lit fraction along x crosses `level`, by linear interpolation (x increasing).
float crossing(const std::vector<glm::vec3>& points, const std::vector<float>& fractions,
               float level) {
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (fractions[i - 1] < level && fractions[i] >= level) {
      const float t = (level - fractions[i - 1]) / (fractions[i] - fractions[i - 1]);
      return glm::mix(points[i - 1].x, points[i].x, t);
    }
  }
  return std::nanf("");
}

TEST(Shadows, PenumbraWidensWithTheDistanceFromTheOccluderAsTheGeometryPredicts) {
  const auto directory = test::scratchDirectory();
  const std::vector<glm::vec3> line = floorLine(0.0f, 2.0f, 101);
  for (const float height : {0.5f, 1.0f}) {
    Scene scene = test::loadSceneText(directory, slabScene(height, 1.0f, kWhiteLight));
    Renderer renderer(scene, {96, 96});
    RenderSettings settings;
    settings.vplsPerLight = 144;
    settings.shadows.enabled = false;
    const Image unshadowed = render(renderer, settings, RenderMode::Naive);
    settings.shadows.enabled = true;
    const Image shadowed = render(renderer, settings, RenderMode::Naive);
    const std::vector<float> fractions =
        litFractions(shadowed, unshadowed, nearestPixels(renderer, line));
    // A light of width W at height H and an edge at height h: the penumbra on the floor is
    // W h / (H - h) wide, and the lit fraction grows almost linearly across it, so 10% to 90%
    // takes 0.8 of it.
    const float predicted = 0.8f * 1.0f * height / (2.0f - height);
    const float measured = crossing(line, fractions, 0.9f) - crossing(line, fractions, 0.1f);
    // 20%: 12 VPLs across the light make the lit fraction a staircase of 12 steps (each
    // crossing within 1/24 of the width), voxels of 3 cm widen the 4 cm slab by up to a voxel
    // on each side, and the pixels are 4.5 cm wide.
    EXPECT_NEAR(measured, predicted, 0.2f * predicted) << "slab at height " << height;
  }
}

TEST(Shadows, PenumbraTakesTheColourOfTheVisibleHalfOfATwoColourLight) {
  const auto directory = test::scratchDirectory();
  // Red on the left half (-x), blue on the right.
  Image picture(2, 1);
  picture.at(0, 0) = glm::vec4(1, 0, 0, 1);
  picture.at(1, 0) = glm::vec4(0, 0, 1, 1);
  saveImage(picture, directory / "red_blue.exr");
  // A 0.6-wide slab at height 1 under the 1-wide light: a floor point at x = -0.5 sees only
  // the light's left part (x < -0.1) past the slab, one at x = 0.5 only its right part.
  Scene scene = test::loadSceneText(
      directory,
      slabScene(1.0f, 0.6f, "material light\n  emit 10 10 10\n  tex red_blue.exr\nend\n"));
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.vplsPerLight = 64;
  for (const RenderMode mode : {RenderMode::Naive, RenderMode::Hierarchical}) {
    settings.shadows.visibleFraction = false;
    const Image image = render(renderer, settings, mode);
    const std::vector<glm::ivec2> pixels =
        nearestPixels(renderer, {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}});
    const glm::vec3 left(image.at(pixels[0].x, pixels[0].y));
    const glm::vec3 right(image.at(pixels[1].x, pixels[1].y));
    // Ideally pure red and pure blue; a factor of 5 leaves room for the VPL columns on the
    // light's middle (a VPL is 1/8 of its width) and the voxels' widening of the slab.
    EXPECT_GT(left.r, 5.0f * left.b) << renderModeName(mode);
    EXPECT_GT(right.b, 5.0f * right.r) << renderModeName(mode);
    // The thesis's shortcut scales the unshadowed light, half red half blue, on both sides.
    settings.shadows.visibleFraction = true;
    const Image shortcut = render(renderer, settings, mode);
    for (const glm::ivec2 pixel : pixels) {
      const glm::vec3 colour(shortcut.at(pixel.x, pixel.y));
      EXPECT_GT(colour.r, 0.5f * colour.b) << renderModeName(mode) << " shortcut";
      EXPECT_LT(colour.r, 2.0f * colour.b) << renderModeName(mode) << " shortcut";
    }
  }
}

TEST(Shadows, MovingTheOccluderMovesItsShadow) {
  const auto directory = test::scratchDirectory();
  // The slab oscillates along its own x axis by sin(0.5 frame), that is along x by
  // 0.6 sin(0.5 frame) after its scale: 0 at frame 0, 0.288 at frame 1.
  Scene scene = test::loadSceneText(
      directory, slabScene(1.0f, 0.6f, kWhiteLight, "  anim translate 1 0 0 0.5\n"));
  Renderer renderer(scene, scene.camera.size);
  const std::vector<glm::vec3> line = floorLine(-2.0f, 2.0f, 161);
  RenderSettings settings;
  settings.vplsPerLight = 64;
  const auto shadowCentre = [&](int frame) {
    settings.shadows.enabled = false;
    const Image unshadowed = render(renderer, settings, RenderMode::Hierarchical, frame);
    settings.shadows.enabled = true;
    const Image shadowed = render(renderer, settings, RenderMode::Hierarchical, frame);
    const std::vector<float> fractions =
        litFractions(shadowed, unshadowed, nearestPixels(renderer, line));
    double weight = 0.0;
    double moment = 0.0;
    for (std::size_t i = 0; i < line.size(); ++i) {
      weight += 1.0 - fractions[i];
      moment += (1.0 - fractions[i]) * line[i].x;
    }
    return moment / weight;
  };
  const double before = shadowCentre(0);
  const double after = shadowCentre(1);
  // From every point of the light, the slab's shadow is its projection onto the floor, which
  // moves by d H / (H - h) = 2d when the slab at h = 1 moves by d (light at H = 2).
  const double expected = 2.0 * 0.6 * std::sin(0.5);
  EXPECT_NEAR(before, 0.0, 0.05);
  // 10%: the voxels (3 cm) round the slab's edges differently in the two frames, which moves
  // its shadow's edges by up to twice that on the floor.
  EXPECT_NEAR(after - before, expected, 0.1 * expected);
}

TEST(Shadows, WorldGridSeesAnOccluderOutsideTheViewAndTheScreenGridDoesNot) {
  Scene scene =
      loadScene(parseSceneFile(test::sourceDirectory() / "scenes/shadow_offscreen.scene"));
  Renderer renderer(scene, {64, 64});
  RenderSettings settings;
  settings.vplsPerLight = 64;
  settings.shadows.enabled = false;
  const Image unshadowed = render(renderer, settings, RenderMode::Hierarchical);
  const std::vector<glm::ivec2> centre = nearestPixels(renderer, {{0.0f, 0.0f, 0.0f}});
  settings.shadows.enabled = true;
  const Image world = render(renderer, settings, RenderMode::Hierarchical);
  settings.shadows.voxels.grid = VoxelSettings::Grid::Screen;
  settings.shadows.voxels.traversal = VoxelSettings::Traversal::Uniform;
  const Image screen = render(renderer, settings, RenderMode::Hierarchical);
  // The floor's centre lies in the slab's umbra (slab 0.8 wide at height 2, light 1 wide at 3).
  EXPECT_EQ(litFractions(world, unshadowed, centre)[0], 0.0f);
  // The screen grid only holds what the camera sees: no slab, no shadow.
  EXPECT_EQ(litFractions(screen, unshadowed, centre)[0], 1.0f);
}

// The image target: the hierarchy against the naive mode with the same grid, relative
// MSE at most 2e-3. Default settings (256 VPLs per light, 192^3 world grid) at 128x128, where a
// coarsest texel covers twice the scene it covers at 256x256. Measured at 256x256
// (docs/shadows.md): box 6.6e-5, Cornell box 3.4e-4 (1.0e-3 before texels took their parents'
// visibility only where the parents' surface stands for theirs).
void expectHierarchyMatchesNaive(const std::string& sceneName) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes" / sceneName));
  Renderer renderer(scene, {128, 128});
  RenderSettings settings;
  const Image naive = render(renderer, settings, RenderMode::Naive);
  const Image hierarchical = render(renderer, settings, RenderMode::Hierarchical);
  const double error = compareImages(hierarchical, naive).relativeMse;
  std::printf("%s: hierarchical against naive, relative MSE %.3g\n", sceneName.c_str(), error);
  EXPECT_LE(error, 2e-3) << sceneName;
}

TEST(Shadows, HierarchyMatchesTheNaiveModeOnTheBox) {
  expectHierarchyMatchesNaive("shadow_box.scene");
}

TEST(Shadows, HierarchyMatchesTheNaiveModeOnTheCornellBoxWithTheBunny) {
  expectHierarchyMatchesNaive("cornell_bunny.scene");
}

// Every texel of the coarsest level traces all its VPLs; below it a texel traces only the VPLs
// on which its parent and the parent's neighbours disagree (visibility_trace.comp), which across
// the box's penumbra is a small part of them. The two tests above check that the image stays
// within the target of the naive one.
TEST(Shadows, FinerLevelsTraceOnlyTheVplsTheParentsNeighboursDisagreeOn) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes/shadow_box.scene"));
  Renderer renderer(scene, {128, 128});
  RenderSettings settings;
  render(renderer, settings, RenderMode::Hierarchical);
  const FrameStatistics statistics = renderer.statistics();
  const auto vpls = static_cast<std::uint64_t>(statistics.vplCount);
  ASSERT_EQ(vpls, 256u);
  ASSERT_GE(statistics.levels.size(), 2u);
  const LevelStatistics& coarsest = statistics.levels.back();
  EXPECT_GT(coarsest.visibilityTraced, 0u);
  EXPECT_EQ(coarsest.shadowRays, coarsest.visibilityTraced * vpls);
  for (std::size_t level = 0; level + 1 < statistics.levels.size(); ++level) {
    const LevelStatistics& finer = statistics.levels[level];
    EXPECT_GT(finer.visibilityTraced, 0u) << "level " << level;
    // Tracing every VPL of the listed texels would give visibilityTraced * vpls. At 128x128 a
    // level-1 texel spans 2 pixels, so the box's penumbra changes over a few texels and their
    // masks disagree on about a third of the VPLs (32% measured); half is the bound.
    EXPECT_LT(finer.shadowRays, finer.visibilityTraced * vpls / 2) << "level " << level;
    std::printf("level %zu: %u texels traced %llu rays (%.1f%% of all their VPLs)\n", level,
                finer.visibilityTraced, static_cast<unsigned long long>(finer.shadowRays),
                100.0 * static_cast<double>(finer.shadowRays) /
                    static_cast<double>(finer.visibilityTraced * vpls));
  }
}

// Which of the G-buffer's points a comparison counts, given the grid's voxel size.
using PointFilter = bool (*)(const test::VoxelQueries::Point& point, glm::vec3 voxelSize);

bool everyPoint(const test::VoxelQueries::Point&, glm::vec3) {
  return true;
}

// Bits of voxel visibility (the GPU's vplVisible through the renderer's grid) that agree with
// Embree's exact visibility for the same points and VPLs: the G-buffer's surface pixels at
// `size` (those `selected` keeps) and 64 VPLs per light, counting only the pairs where the VPL
// can light the point (both face each other), so that trivially visible pairs do not inflate
// the figure.
double agreementWithEmbree(Scene& scene, const std::string& sceneName,
                           PointFilter selected = everyPoint, glm::ivec2 size = {64, 64}) {
  Renderer renderer(scene, size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 64;
  renderer.render(0, settings);

  const glm::vec3 voxelSize(renderer.voxelGrid().description.voxelSize);
  std::vector<test::VoxelQueries::Point> points = test::surfacePoints(renderer.gbuffer());
  std::erase_if(
      points, [&](const test::VoxelQueries::Point& point) { return !selected(point, voxelSize); });
  std::vector<test::VoxelQueries::Vpl> vpls;
  for (const Light& light : scene.lights)
    for (const Vpl& vpl : makeVpls(light.quad, light.emission, nullptr, 8))
      vpls.push_back({vpl.position, vpl.normal});

  test::VoxelQueries queries;
  queries.useGrid(renderer.voxelGrid().header.id(), renderer.voxelGrid().words.id());
  const std::vector<bool> voxelVisible = queries.vplsVisible(points, vpls);

  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  const RayScene rays(geometry, scene.lights);
  // The reference renderer's offsets: off the surface by 1e-4 of the scene's diagonal, and
  // stopping just short of the VPL so that its own quad does not block it.
  const float offset = 1e-4f * glm::length(geometry.boundsMax - geometry.boundsMin);
  std::size_t pairs = 0;
  std::size_t agreeing = 0;
  std::size_t blockedByTheGridOnly = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    for (std::size_t v = 0; v < vpls.size(); ++v) {
      const glm::vec3 towardsVpl = vpls[v].position - points[p].position;
      if (glm::dot(towardsVpl, points[p].normal) <= 0.0f ||
          glm::dot(towardsVpl, vpls[v].normal) >= 0.0f)
        continue;
      const glm::vec3 origin = points[p].position + offset * points[p].normal;
      const glm::vec3 toVpl = vpls[v].position - origin;
      const float distance = glm::length(toVpl);
      const bool exact = !rays.occluded(origin, toVpl / distance, (1.0f - 1e-4f) * distance);
      ++pairs;
      agreeing += exact == voxelVisible[p * vpls.size() + v] ? 1 : 0;
      blockedByTheGridOnly += exact && !voxelVisible[p * vpls.size() + v] ? 1 : 0;
    }
  }
  EXPECT_GT(pairs, 10000u) << sceneName;
  const double agreement = static_cast<double>(agreeing) / static_cast<double>(pairs);
  ::testing::Test::RecordProperty("agreement", std::to_string(agreement));
  std::printf("%s: %.4f of %zu bits agree with Embree (%zu blocked by the grid only)\n",
              sceneName.c_str(), agreement, pairs, blockedByTheGridOnly);
  return agreement;
}

double agreementWithEmbree(const std::string& sceneName) {
  Scene scene = loadScene(parseSceneFile(test::sourceDirectory() / "scenes" / sceneName));
  return agreementWithEmbree(scene, sceneName);
}

// The target: at least 95% of the bits agree on each scene. The rest are rays that
// graze occluders, whose voxels are larger than the occluders: the default grid (192^3) was
// chosen as the coarsest that meets the target on every scene (docs/shadows.md); at 128^3 the
// thin posts reach only 0.890 and the off-screen slab 0.944.
constexpr double kMinimumAgreement = 0.95;

TEST(VoxelVisibility, AgreesWithEmbreeOnTheBoxScene) {
  EXPECT_GE(agreementWithEmbree("shadow_box.scene"), kMinimumAgreement);
}

TEST(VoxelVisibility, AgreesWithEmbreeOnTheTwoColourScene) {
  EXPECT_GE(agreementWithEmbree("shadow_two_colour.scene"), kMinimumAgreement);
}

TEST(VoxelVisibility, AgreesWithEmbreeOnTheCornellBoxWithTheBunny) {
  EXPECT_GE(agreementWithEmbree("cornell_bunny.scene"), kMinimumAgreement);
}

TEST(VoxelVisibility, AgreesWithEmbreeOnTheThinPosts) {
  EXPECT_GE(agreementWithEmbree("shadow_posts.scene"), kMinimumAgreement);
}

TEST(VoxelVisibility, AgreesWithEmbreeOnTheOffscreenOccluder) {
  EXPECT_GE(agreementWithEmbree("shadow_offscreen.scene"), kMinimumAgreement);
}

TEST(VoxelVisibility, AgreesWithEmbreeOnTheDemo) {
  EXPECT_GE(agreementWithEmbree("demo.scene"), kMinimumAgreement);
}

// Points within a voxel of a perpendicular surface start their rays inside that surface's
// voxels (every surface grows to the voxel boundaries around it). The light near the wall
// without its rod: a floor (y = 0) meets a wall (z = -1) under a panel 10 cm from the wall; its
// floor points within a voxel of the wall and its wall points within a voxel of the floor.
// Before the traversal left the occupied voxels a ray starts in, 17% of their bits
// agreed with Embree (nearly every ray blocked: a dark seam); now 99%. The bound is the
// other scenes' target.
std::string wallAndFloorScene() {
  const std::string floor = quoted(test::sourceDirectory() / "scenes/assets/floor.obj");
  return "material wall\n  dif 0.8 0.8 0.8\nend\n"
         "material glow\n  emit 5 5 5\nend\n"
         "area_light panel\n  pos1 -0.5 1.0 -0.9\n  pos2 0.5 1.0 -0.9\n  pos3 0.5 1.0 -0.3\n"
         "  pos4 -0.5 1.0 -0.3\n  at 0 0 -0.6\n  mat glow\nend\n"
         "camera view\n  pos 0.6 0.9 1.4\n  at 0 0.45 -0.8\n  fovy 50\n  near 0.05\n  far 20\nend\n"
         "object " +
         floor + "\n  scale 6\n  mat wall\nend\n" + "object " + floor +
         "\n  translate 0 0 -1\n  rotate 90 1 0 0\n  scale 6\n  mat wall\nend\n";
}

bool withinAVoxelOfTheWallsFoot(const test::VoxelQueries::Point& point, glm::vec3 voxelSize) {
  const bool onFloor = point.normal.y > 0.9f;
  const bool onWall = point.normal.z > 0.9f;
  return (onFloor && point.position.z < -1.0f + voxelSize.z) ||
         (onWall && point.position.y < voxelSize.y);
}

TEST(VoxelVisibility, PointsWithinAVoxelOfAPerpendicularSurfaceAgreeWithEmbree) {
  Scene scene = test::loadSceneText(test::scratchDirectory(), wallAndFloorScene());
  EXPECT_GE(agreementWithEmbree(scene, "the wall's foot", withinAVoxelOfTheWallsFoot, {256, 256}),
            kMinimumAgreement);
}

}  // namespace
}  // namespace penumbra
