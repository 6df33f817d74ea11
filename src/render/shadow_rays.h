#pragma once
// What answers a frame's shadow queries (vplVisible in shaders/shadow_rays.glsl): the voxel grid
// or the exact hierarchy (--visibility, docs/shadows.md); and the variants of a program that
// traces shadow rays: the default voxel grid's, any other grid's and the hierarchy's, the last two
// compiled only once they are used.

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/program.h"
#include "render/bvh_gpu.h"
#include "render/voxelize.h"

namespace penumbra {

// Exactly one of the two is set.
struct ShadowRays {
  const VoxelGrid* grid = nullptr;
  const BvhGpu* bvh = nullptr;

  // Binds the buffers the chosen method's shaders read.
  void bind() const;
};

class ShadowRayProgram {
 public:
  // defines: compiled into every variant, besides the variant's own.
  explicit ShadowRayProgram(std::string fileName, std::vector<std::string> defines = {});
  // The variant for `rays`.
  const gl::Program& forRays(const ShadowRays& rays) const;
  // The variant for `rays`, or the default grid's without shadow rays (null), whose shadow code
  // does not run.
  const gl::Program& forRays(const ShadowRays* rays) const {
    return rays != nullptr ? forRays(*rays) : defaultGrid_;
  }

 private:
  gl::Program compile(const char* variantDefine) const;

  std::string fileName_;
  std::vector<std::string> defines_;
  // The voxel variants: one for the default grid (a world grid walked exactly, not widened, with
  // boxes inside its voxels), whose modes are constants in it (voxel_grid.glsl says why), and one
  // that reads them from the grid, for the others. Only the first is compiled up front.
  gl::Program defaultGrid_;
  mutable std::optional<gl::Program> anyGrid_;
  mutable std::optional<gl::Program> bvh_;
};

// Whether a grid is the default grid that ShadowRayProgram has a variant of its own for.
bool isDefaultVoxelGrid(const gpu::GpuVoxelGrid& grid);

// Dispatches `program` (in use, its images and buffers bound) over a size.x x size.y grid once
// per batch of `batch` VPLs, setting its firstVpl and endVpl uniforms; each batch adds to what
// the earlier ones wrote. Shadow rays go in batches of the device profile's rays per dispatch
// (one long dispatch runs into llvmpipe's loop limit); without them one batch of every VPL.
void dispatchInVplBatches(const gl::Program& program, glm::ivec2 size, int vplCount, int batch);

}  // namespace penumbra
