// The shadow-ray traversal of shaders/voxel_grid.glsl, run by a test kernel on small hand-built
// grids, against a C++ reference that follows the definitions: the exact traversal is blocked
// when the segment passes through an occupied voxel (tested box by box) after leaving the
// occupied voxels it starts in (at most two), uniform stepping when one of its samples
// (or, widened, one of the 8 voxels nearest a sample) is occupied.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/shadow_rays.h"
#include "render/voxel_queries.h"
#include "shared.h"

namespace penumbra {
namespace {

// A world grid whose voxels the test sets one by one, with its words laid out as
// voxel_grid.glsl documents.
class HandGrid {
 public:
  HandGrid(glm::ivec3 size, glm::vec3 boundsMin, glm::vec3 voxelSize) : size_(size) {
    description_.resolution = {size.x, size.y, size.z, (size.z + 31) / 32};
    description_.modes = {gpu::kGridWorld, gpu::kTraversalDda, 16, 0};
    description_.boundsMin = glm::vec4(boundsMin, 0.0f);
    description_.voxelSize = glm::vec4(voxelSize, 0.0f);
    occupied_.assign(static_cast<std::size_t>(size.x) * size.y * size.z, false);
  }

  glm::ivec3 size() const { return size_; }
  void set(glm::ivec3 voxel) {
    occupied_[index(voxel)] = true;
    occupiedList_.push_back(voxel);
  }
  const std::vector<glm::ivec3>& occupiedVoxels() const { return occupiedList_; }
  bool occupied(glm::ivec3 voxel) const {
    if (glm::any(glm::lessThan(voxel, glm::ivec3(0))) ||
        glm::any(glm::greaterThanEqual(voxel, size_)))
      return false;
    return occupied_[index(voxel)];
  }
  void setTraversal(int traversal, int steps, bool widen) {
    description_.modes = {gpu::kGridWorld, traversal, steps, widen ? 1 : 0};
  }
  glm::vec3 toGrid(glm::vec3 world) const {
    return (world - glm::vec3(description_.boundsMin)) / glm::vec3(description_.voxelSize);
  }
  glm::vec3 toWorld(glm::vec3 grid) const {
    return glm::vec3(description_.boundsMin) + grid * glm::vec3(description_.voxelSize);
  }

  // Uploads the header and every block of words.
  void upload() {
    std::vector<std::uint32_t> words(test::voxelWordCount(size_, true), 0u);
    for (int z = 0; z < size_.z; ++z) {
      for (int y = 0; y < size_.y; ++y) {
        for (int x = 0; x < size_.x; ++x) {
          if (!occupied({x, y, z}))
            continue;
          for (int axis = 0; axis < 3; ++axis) {
            const auto [word, bit] = test::voxelLocation(size_, axis, {x, y, z});
            words[word] |= 1u << bit;
          }
        }
      }
    }
    glNamedBufferData(header_.id(), sizeof(description_), &description_, GL_STATIC_DRAW);
    glNamedBufferData(words_.id(), static_cast<GLsizeiptr>(words.size() * 4), words.data(),
                      GL_STATIC_DRAW);
  }
  GLuint header() const { return header_.id(); }
  GLuint words() const { return words_.id(); }

 private:
  std::size_t index(glm::ivec3 voxel) const {
    return (static_cast<std::size_t>(voxel.z) * size_.y + voxel.y) * size_.x + voxel.x;
  }
  glm::ivec3 size_;
  gpu::GpuVoxelGrid description_{};
  std::vector<bool> occupied_;
  std::vector<glm::ivec3> occupiedList_;
  gl::Buffer header_;
  gl::Buffer words_;
};

// Whether the segment a-b (grid coordinates) passes through the box [low, high] for a parameter
// interval of positive length (slab test).
bool segmentCrossesBox(glm::dvec3 a, glm::dvec3 b, glm::dvec3 low, glm::dvec3 high) {
  double enter = 0.0;
  double leave = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double delta = b[axis] - a[axis];
    if (delta == 0.0) {
      if (a[axis] <= low[axis] || a[axis] >= high[axis])
        return false;
      continue;
    }
    double t0 = (low[axis] - a[axis]) / delta;
    double t1 = (high[axis] - a[axis]) / delta;
    if (t0 > t1)
      std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  return enter < leave;
}

// The exact answer with every voxel grown (margin > 0) or shrunk (margin < 0) on each side.
bool exactlyBlocked(const HandGrid& grid, glm::dvec3 a, glm::dvec3 b, double margin) {
  return std::any_of(grid.occupiedVoxels().begin(), grid.occupiedVoxels().end(),
                     [&](glm::ivec3 voxel) {
                       return segmentCrossesBox(a, b, glm::dvec3(voxel) - margin,
                                                glm::dvec3(voxel) + 1.0 + margin);
                     });
}

// How the exact traversal starts (leaveStartContents in voxel_grid.glsl): a segment that starts
// inside the grid in the contents of occupied voxels (here, without boxes, the whole voxels)
// leaves at most kStartContentsLeft of them along a 3D DDA and is blocked when it is still in one
// after them.
constexpr int kStartContentsLeft = 2;

struct SegmentStart {
  bool blocked = false;
  double enter = 0.0;      // the parameter from which every voxel counts
  double exitStep = 0.0;   // the parameter's step per voxel along the axis it left the last by
  bool ambiguous = false;  // float rounding may step differently (boundaries within 1e-6)
};

SegmentStart leaveStartContents(const HandGrid& grid, glm::dvec3 a, glm::dvec3 b) {
  SegmentStart start;
  if (glm::any(glm::lessThan(a, glm::dvec3(0.0))) ||
      glm::any(glm::greaterThanEqual(a, glm::dvec3(grid.size()))))
    return start;
  const glm::dvec3 direction = b - a;
  glm::ivec3 voxel(glm::floor(a));
  glm::dvec3 boundary;
  glm::dvec3 step;
  for (int axis = 0; axis < 3; ++axis) {
    const double along = direction[axis];
    const double next = along > 0.0 ? voxel[axis] + 1.0 : voxel[axis];
    boundary[axis] =
        along == 0.0 ? std::numeric_limits<double>::infinity() : (next - a[axis]) / along;
    step[axis] = along == 0.0 ? std::numeric_limits<double>::infinity() : std::abs(1.0 / along);
  }
  for (int i = 0; i < kStartContentsLeft && grid.occupied(voxel); ++i) {
    int axis = 0;
    for (int other = 1; other < 3; ++other)
      axis = boundary[other] < boundary[axis] ? other : axis;
    for (int other = 0; other < 3; ++other)
      start.ambiguous =
          start.ambiguous || (other != axis && std::abs(boundary[other] - boundary[axis]) < 1e-6);
    if (boundary[axis] >= 1.0) {
      start.blocked = true;
      return start;
    }
    start.enter = boundary[axis];
    start.exitStep = step[axis];
    voxel[axis] += direction[axis] > 0.0 ? 1 : -1;
    boundary[axis] += step[axis];
  }
  start.blocked = grid.occupied(voxel);
  return start;
}

// A grid of 40 x 20 x 64 voxels (two words along x and z, one along y), with non-cubic voxels
// away from the origin, about 3% of them occupied at random plus a wall across x.
HandGrid makeTestGrid() {
  HandGrid grid({40, 20, 64}, {-1.5f, 2.0f, 0.25f}, {0.5f, 0.25f, 0.125f});
  std::mt19937 random(7);
  std::uniform_int_distribution<int> percent(0, 99);
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 40; ++x)
        if (percent(random) < 3 || (x == 30 && y < 12))
          grid.set({x, y, z});
  grid.upload();
  return grid;
}

// Segments in grid coordinates: random ends in a box a little larger than the grid (so that
// the kernel clips them), a quarter of them parallel to one or two axes.
std::vector<glm::dvec3> makeSegments(glm::ivec3 size, int count) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::dvec3> ends;
  for (int i = 0; i < count; ++i) {
    glm::dvec3 a;
    glm::dvec3 b;
    for (int axis = 0; axis < 3; ++axis) {
      a[axis] = -3.0 + (size[axis] + 6.0) * unit(random);
      b[axis] = -3.0 + (size[axis] + 6.0) * unit(random);
    }
    if (i % 4 == 0)
      b[i % 3] = a[i % 3];
    if (i % 8 == 0)
      b[(i + 1) % 3] = a[(i + 1) % 3];
    ends.push_back(a);
    ends.push_back(b);
  }
  return ends;
}

std::vector<glm::vec3> toWorld(const HandGrid& grid, const std::vector<glm::dvec3>& ends) {
  std::vector<glm::vec3> world;
  for (const glm::dvec3 end : ends)
    world.push_back(grid.toWorld(glm::vec3(end)));
  return world;
}

TEST(VoxelTraversal, ExactTraversalIsBlockedExactlyByTheVoxelsTheSegmentCrosses) {
  HandGrid grid = makeTestGrid();
  grid.setTraversal(gpu::kTraversalDda, 1, false);
  grid.upload();
  test::VoxelQueries queries;
  queries.useGrid(grid.header(), grid.words());
  const std::vector<glm::dvec3> ends = makeSegments(grid.size(), 1500);
  const std::vector<bool> blocked = queries.segmentsBlocked(toWorld(grid, ends));

  int decided = 0;
  int blockedCount = 0;
  int startsLeft = 0;
  for (std::size_t i = 0; i < blocked.size(); ++i) {
    const glm::dvec3 a = ends[2 * i];
    const glm::dvec3 b = ends[2 * i + 1];
    const SegmentStart start = leaveStartContents(grid, a, b);
    if (start.ambiguous)
      continue;
    bool surely = start.blocked;
    bool possibly = start.blocked;
    if (!start.blocked) {
      // The kernel works in float: a segment that passes within 1e-3 voxel of an occupied voxel
      // may go either way; every other segment has one right answer. The voxel the start left
      // touches the rest of the segment, which therefore starts 2e-3 voxel further on.
      const double enter = start.enter == 0.0 ? 0.0 : start.enter + 2e-3 * start.exitStep;
      const glm::dvec3 from = glm::mix(a, b, std::min(enter, 1.0));
      surely = exactlyBlocked(grid, from, b, -1e-3);
      possibly = exactlyBlocked(grid, from, b, 1e-3);
      startsLeft += start.enter > 0.0 ? 1 : 0;
    }
    if (surely != possibly)
      continue;
    ++decided;
    blockedCount += surely ? 1 : 0;
    EXPECT_EQ(blocked[i], surely) << "segment " << i << " from " << a.x << "," << a.y << "," << a.z
                                  << " to " << b.x << "," << b.y << "," << b.z;
  }
  // The test means something only if nearly every segment is decided, both answers occur, and
  // some segments start in occupied voxels.
  EXPECT_GT(decided, 1400);
  EXPECT_GT(blockedCount, 300);
  EXPECT_LT(blockedCount, decided - 300);
  EXPECT_GT(startsLeft, 20);
}

TEST(VoxelTraversal, ExactTraversalLeavesTheOccupiedVoxelsItStartsInButNotAThickWall) {
  // A wall one voxel thick at x = 2 and one four voxels thick at x = 10 to 13, in unit voxels.
  HandGrid grid({16, 8, 32}, {0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
  for (int z = 0; z < 32; ++z) {
    for (int y = 0; y < 8; ++y) {
      grid.set({2, y, z});
      for (int x = 10; x < 14; ++x)
        grid.set({x, y, z});
    }
  }
  grid.setTraversal(gpu::kTraversalDda, 1, false);
  grid.upload();
  test::VoxelQueries queries;
  queries.useGrid(grid.header(), grid.words());
  const std::vector<glm::vec3> ends = {
      // Starts in the thin wall and leaves it either way: not blocked.
      {2.5f, 4.2f, 4.3f},
      {7.5f, 5.1f, 6.2f},
      {2.5f, 4.2f, 4.3f},
      {0.5f, 3.1f, 6.2f},
      // Leaves the thin wall, then meets the thick one: blocked.
      {2.5f, 4.2f, 4.3f},
      {15.5f, 5.1f, 6.2f},
      // Starts in the thick wall, three voxels from its far side, along x (its y and z stay in
      // their voxels): still inside after leaving two, blocked.
      {11.5f, 4.2f, 4.3f},
      {15.5f, 4.6f, 4.8f},
      // Two voxels from its far side: leaves it.
      {12.5f, 4.2f, 4.3f},
      {15.5f, 4.6f, 4.8f},
      // Outside the grid, entering it through the thin wall's voxel at its side: blocked, it does
      // not start in it.
      {-3.0f, 4.2f, 4.3f},
      {2.9f, 4.3f, 4.4f},
      // Starting in a free voxel next to the thin wall and crossing it: blocked.
      {1.5f, 4.2f, 4.3f},
      {5.5f, 4.3f, 4.4f}};
  const std::vector<bool> blocked = queries.segmentsBlocked(ends);
  const std::vector<bool> expected = {false, false, true, true, false, true, true};
  ASSERT_EQ(blocked.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(blocked[i], expected[i]) << "segment " << i;
}

TEST(VoxelTraversal, UniformSteppingTestsTheVoxelsOfItsSamples) {
  HandGrid grid = makeTestGrid();
  test::VoxelQueries queries;
  const std::vector<glm::dvec3> ends = makeSegments(grid.size(), 1500);
  for (const bool widen : {false, true}) {
    constexpr int kSteps = 12;
    grid.setTraversal(gpu::kTraversalUniform, kSteps, widen);
    grid.upload();
    queries.useGrid(grid.header(), grid.words());
    const std::vector<bool> blocked = queries.segmentsBlocked(toWorld(grid, ends));
    int decided = 0;
    for (std::size_t i = 0; i < blocked.size(); ++i) {
      bool expected = false;
      bool ambiguous = false;
      for (int step = 0; step < kSteps; ++step) {
        const double t = (step + 0.5) / kSteps;
        // Widening tests the 2x2x2 voxels around the sample: those from floor(p - 0.5).
        const glm::dvec3 sample = glm::mix(ends[2 * i], ends[2 * i + 1], t) - (widen ? 0.5 : 0.0);
        const glm::dvec3 fraction = sample - glm::floor(sample);
        // A sample within 1e-3 voxel of a boundary may fall on either side in float.
        if (glm::any(glm::lessThan(glm::min(fraction, 1.0 - fraction), glm::dvec3(1e-3))))
          ambiguous = true;
        const glm::ivec3 first(glm::floor(sample));
        for (int corner = 0; corner < (widen ? 8 : 1); ++corner)
          expected = expected ||
                     grid.occupied(first + glm::ivec3(corner & 1, (corner >> 1) & 1, corner >> 2));
      }
      if (ambiguous)
        continue;
      ++decided;
      EXPECT_EQ(blocked[i], expected) << "segment " << i << (widen ? " (widened)" : "");
    }
    EXPECT_GT(decided, 1200) << (widen ? "widened" : "");
  }
}

TEST(VoxelTraversal, ExactTraversalSeesAVoxelThatUniformSteppingStepsOver) {
  // One occupied voxel in the middle of an empty grid, and a segment 40 voxels long through
  // it: 4 samples are 10 voxels apart and miss it; the exact traversal does not.
  HandGrid grid({40, 20, 64}, {0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});
  grid.set({20, 10, 32});
  test::VoxelQueries queries;
  const std::vector<glm::vec3> ends = {grid.toWorld({0.2f, 10.5f, 32.5f}),
                                       grid.toWorld({39.8f, 10.5f, 32.5f})};
  grid.setTraversal(gpu::kTraversalUniform, 4, false);
  grid.upload();
  queries.useGrid(grid.header(), grid.words());
  EXPECT_FALSE(queries.segmentsBlocked(ends)[0]);
  grid.setTraversal(gpu::kTraversalDda, 4, false);
  grid.upload();
  EXPECT_TRUE(queries.segmentsBlocked(ends)[0]);
}

TEST(VoxelTraversal, WorldGridMapsPointsToVoxelCoordinates) {
  HandGrid grid = makeTestGrid();
  test::VoxelQueries queries;
  queries.useGrid(grid.header(), grid.words());
  const std::vector<glm::vec3> points = {
      {-1.5f, 2.0f, 0.25f}, {0.0f, 3.0f, 1.0f}, {18.5f, 7.0f, 8.25f}};
  const std::vector<glm::vec3> coordinates = queries.gridCoordinates(points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 expected = grid.toGrid(points[i]);
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(coordinates[i][axis], expected[axis], 1e-4) << "point " << i << " axis " << axis;
  }
}

// The programs compiled for the default grid hold its modes as constants (voxel_grid.glsl): any
// other mode must get the program that reads them from the grid.
TEST(VoxelTraversal, OnlyTheDefaultGridGetsTheProgramsOfTheDefaultGrid) {
  gpu::GpuVoxelGrid grid{};
  grid.modes = {gpu::kGridWorld, gpu::kTraversalDda, 16, 0};
  grid.occupancy = {6, 100, 200, 8};
  EXPECT_TRUE(isDefaultVoxelGrid(grid));

  gpu::GpuVoxelGrid screen = grid;
  screen.modes.x = gpu::kGridScreen;
  EXPECT_FALSE(isDefaultVoxelGrid(screen));
  gpu::GpuVoxelGrid uniform = grid;
  uniform.modes.y = gpu::kTraversalUniform;
  EXPECT_FALSE(isDefaultVoxelGrid(uniform));
  gpu::GpuVoxelGrid widened = grid;
  widened.modes.w = 1;
  EXPECT_FALSE(isDefaultVoxelGrid(widened));
  gpu::GpuVoxelGrid withoutBoxes = grid;
  withoutBoxes.occupancy.y = 0;
  EXPECT_FALSE(isDefaultVoxelGrid(withoutBoxes));
}

}  // namespace
}  // namespace penumbra
