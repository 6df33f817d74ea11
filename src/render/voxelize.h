#pragma once
// Pass: voxelization, rebuilt every frame so moving objects cast moving shadows. Surfaces and
// light quads (opaque to other lights) mark a bit grid: over the scene's bounds in world space
// (the default: it sees occluders outside the view), or the paper's screen-space grid over the
// camera frustum.

#include <array>
#include <cstddef>

#include "gl/handles.h"
#include "gl/program.h"
#include "render/scene_gpu.h"
#include "shared.h"

namespace penumbra {

struct VoxelSettings {
  enum class Grid { World, Screen };
  enum class Fill { Surface, Solid };
  enum class Traversal { Uniform, Dda };
  // World grid: `resolution` voxels along every axis (equal), or as many voxels as a cube of
  // `resolution` a side shared out in proportion to the sides of the scene's box (cubic), so
  // that a flat scene's voxels are not flat.
  enum class Shape { Equal, Cubic };
  Grid grid = Grid::World;
  Fill fill = Fill::Surface;
  // Cubic 304 brings every shadow scene within issue 15's bounds at 1.1 to 1.3 times the cost of
  // equal 192 (docs/shadows.md, "Cubic voxels").
  Shape shape = Shape::Cubic;
  int resolution = 304;   // world: see Shape; screen: columns per side
  int depthSlices = 128;  // screen grid: slices along the view depth, a multiple of 32
  Traversal traversal = Traversal::Dda;
  int steps = 32;      // uniform traversal: samples per shadow ray
  bool widen = false;  // test the 2x2x2 voxels nearest each sample
  // World grid: the box and slabs of the surfaces inside each occupied voxel, which the
  // traversal tests instead of the whole voxel (GpuVoxelGrid::occupancy); off, every voxel
  // blocks whole.
  bool boxes = true;
  // A shadow ray starts off its surface along the normal by this many times the reach of what
  // the surface marks (voxel_grid.glsl, surfaceOffset), and stops this many times the voxel layer
  // of the light's plane short of it (lightEndFraction).
  float originOffset = 1.25f;
  bool operator==(const VoxelSettings&) const = default;
};

// Largest voxel grid the renderer allocates, and most voxels along one axis.
inline constexpr std::size_t kMaxVoxelGridBytes = std::size_t{1} << 30;
inline constexpr int kMaxVoxelsPerAxis = 4096;

struct VoxelGrid {
  gpu::GpuVoxelGrid description{};
  gl::Buffer header;
  gl::Buffer words;
  std::size_t wordCount = 0;
  // Scratch of the world voxelization: lists of the triangles that span more than one voxel and
  // more than one tile of columns (voxelize_world.comp), each of up to triangleListCapacity.
  gl::Buffer triangleLists;
  unsigned triangleListCapacity = 0;
  // Bricks of the pool of boxes inside the voxels (GpuVoxelGrid::occupancy); grown when a frame
  // needs more.
  unsigned brickCapacity = 0;
};

// The box a grid covers in world space; a screen grid's depth range spans it.
struct VoxelGridBox {
  glm::vec3 low;
  glm::vec3 high;
};

// Bytes of a grid with these settings over a box with sides `boxSize` (a world grid's shape follows
// it) and a pool of `brickCapacity` bricks of boxes inside the voxels (none without boxes). Throws
// RenderError when the settings are out of range or the grid would not fit the limit.
std::size_t voxelGridBytes(const VoxelSettings& settings, glm::vec3 boxSize,
                           unsigned brickCapacity = 0);

class VoxelizePass {
 public:
  struct Inputs {
    const SceneGpu& scene;
    const Camera& camera;  // the screen grid follows its frustum
    const VoxelSettings& settings;
  };
  struct Outputs {
    VoxelGrid& grid;
  };

  VoxelizePass();
  void run(const Inputs& in, const Outputs& out) const;

 private:
  // Everything above once; returns the bricks the frame needs (0 without boxes).
  unsigned voxelize(const Inputs& in, const VoxelGridBox& box, VoxelGrid& grid) const;
  // The world voxelization's three passes: a solid fill's insides, the surfaces' voxels, and, once
  // the bricks are handed out, the boxes inside them.
  // voxelize_world.comp's passes, by the codes the shader knows them by.
  enum class WorldPass : int {
    Solid = gpu::kVoxelizeSolid,
    Surface = gpu::kVoxelizeSurface,
    PlaneNormals = gpu::kVoxelizePlaneNormals,
    Boxes = gpu::kVoxelizeBoxes
  };
  void voxelizeWorld(const SceneGpu& scene, VoxelGrid& grid, WorldPass pass) const;
  void voxelizeScreen(const SceneGpu& scene, const Camera& camera, VoxelGrid& grid,
                      bool solid) const;
  // Copies the columns along z into the columns along x and y of a world grid.
  void transposeColumns(VoxelGrid& grid) const;
  // Builds the occupancy pyramid of a world grid from its columns (GpuVoxelGrid::occupancy).
  void buildOccupancy(VoxelGrid& grid) const;

  // voxelize_world.comp for each pass and dispatch (kVoxelizeEveryTriangle, ...); the solid pass
  // has no dispatch of spanning triangles.
  static constexpr std::size_t kWorldDispatches = 3;
  using WorldPrograms = std::array<std::array<gl::Program, kWorldDispatches>, 4>;
  static WorldPrograms compileWorldPrograms();
  WorldPrograms world_;
  gl::Program screen_;
  gl::Program transpose_;
  gl::Program occupancy_;
  gl::Program bricks_;
  gl::Framebuffer emptyFramebuffer_;
};

}  // namespace penumbra
