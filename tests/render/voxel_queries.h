#pragma once
// Runs the test kernel tests/data/shaders/voxel_queries.comp, which answers queries on a voxel
// grid through the renderer's shaders/voxel_grid.glsl.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/gbuffer.h"
#include "shared.h"

namespace penumbra::test {

// The layout of a grid's words as voxel_grid.glsl documents it, for a grid of `resolution`
// voxels (GpuVoxelGrid::resolution.xyz): blocks of columns along z, x and y in this order; the
// column along `axis` through (u, v) = (coordinate (axis + 1) % 3, coordinate (axis + 2) % 3)
// is column v * resolution_u + u of its block. Screen grids have the block along z only.
std::size_t voxelWordCount(glm::ivec3 resolution, bool allAxes);
// Words of a world grid's occupancy pyramid (GpuVoxelGrid::occupancy), after the columns.
std::size_t occupancyWordCount(const gpu::GpuVoxelGrid& grid);
// Words of a world grid's boxes inside the voxels (GpuVoxelGrid::occupancy), after the occupancy
// pyramid: the count of bricks, the brick table and the pool; 0 without boxes.
std::size_t boxWordCount(const gpu::GpuVoxelGrid& grid);
// What a grid's words hold about the surfaces inside an occupied voxel, in grid coordinates, as
// voxel_content.glsl documents it: the box of slices, and the two slabs around planes (heights
// from the voxel's centre along a unit normal). Without boxes, the whole voxel and no slabs.
struct VoxelSlab {
  glm::vec3 normal{0.0f};
  float low = 0.0f;
  float high = 0.0f;
};
struct VoxelContent {
  glm::vec3 low{0.0f};
  glm::vec3 high{0.0f};
  std::vector<VoxelSlab> slabs;
};
VoxelContent voxelContent(const std::vector<std::uint32_t>& words, const gpu::GpuVoxelGrid& grid,
                          glm::ivec3 voxel);
// Word and bit of a voxel in the block along `axis`.
std::pair<std::size_t, unsigned> voxelLocation(glm::ivec3 resolution, int axis, glm::ivec3 voxel);

class VoxelQueries {
 public:
  VoxelQueries();

  // Binds the grid (header and words buffers) that the next queries read.
  void useGrid(GLuint header, GLuint words);

  // For each segment (from, to): whether the grid's traversal finds it blocked. ColumnsOnly
  // walks every column of the exact traversal, without skipping the occupancy pyramid's cells.
  enum class Walk { AsRendered, ColumnsOnly };
  std::vector<bool> segmentsBlocked(const std::vector<glm::vec3>& ends,
                                    Walk walk = Walk::AsRendered) const;
  // For each point (position, unit normal) and each VPL: whether vplVisible sees the VPL,
  // point-major (result [p * vplCount + v]).
  struct Point {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
  };
  struct Vpl {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
  };
  std::vector<bool> vplsVisible(const std::vector<Point>& points,
                                const std::vector<Vpl>& vpls) const;
  // For each point: whether the clear-light test (lightClearFrom) passes from it to the quad.
  std::vector<bool> lightClear(const std::vector<Point>& points,
                               const std::array<glm::vec3, 4>& corners,
                               glm::vec3 lightNormal) const;
  // Continuous grid coordinates of each point.
  std::vector<glm::vec3> gridCoordinates(const std::vector<glm::vec3>& points) const;

 private:
  std::vector<glm::vec4> run(int query, const std::vector<glm::vec4>& ends, std::size_t count,
                             int vplCount) const;

  gl::Program program_;
  GLuint header_ = 0;
  GLuint words_ = 0;
  gl::Buffer vpls_;
};

// The G-buffer's surface pixels (position and normal), row by row from the top.
std::vector<VoxelQueries::Point> surfacePoints(const GBuffer& gbuffer);

}  // namespace penumbra::test
