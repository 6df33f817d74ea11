#pragma once
// Dispatches by thread count; the work-group size comes from the shader.

#include "gl/program.h"

namespace penumbra::gl {

// Work groups per dimension of a dispatch that every GL 4.3 implementation accepts
// (GL_MAX_COMPUTE_WORK_GROUP_COUNT's minimum); llvmpipe accepts no more.
inline constexpr unsigned kMaxWorkGroupsPerDimension = 65535;

inline void dispatchThreads(const Program& program, glm::ivec2 threads) {
  program.use();
  const glm::uvec3 groups =
      program.groupsFor({static_cast<unsigned>(threads.x), static_cast<unsigned>(threads.y), 1u});
  glDispatchCompute(groups.x, groups.y, groups.z);
}

// Dispatches `count` invocations of linear work, one per item of a list: past
// kMaxWorkGroupsPerDimension work groups they go in rows along y, as few and as even as may be,
// and the shader reads the item's index from linearInvocationIndex()
// (shaders/linear_dispatch.glsl).
inline void dispatchLinear(const Program& program, unsigned count) {
  program.use();
  const unsigned groups = program.groupsFor({count, 1u, 1u}).x;
  const unsigned rows = (groups + kMaxWorkGroupsPerDimension - 1) / kMaxWorkGroupsPerDimension;
  glDispatchCompute(rows == 0 ? 0 : (groups + rows - 1) / rows, rows, 1);
}

}  // namespace penumbra::gl
