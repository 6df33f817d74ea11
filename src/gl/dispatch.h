#pragma once
// Dispatches by thread count; the work-group size comes from the shader.

#include "gl/program.h"

namespace penumbra::gl {

inline void dispatchThreads(const Program& program, glm::ivec2 threads) {
  program.use();
  const glm::uvec3 groups =
      program.groupsFor({static_cast<unsigned>(threads.x), static_cast<unsigned>(threads.y), 1u});
  glDispatchCompute(groups.x, groups.y, groups.z);
}

}  // namespace penumbra::gl
