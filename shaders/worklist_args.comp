#version 450 core
#extension GL_GOOGLE_include_directive : require
// Turns each level's texel count into the work-group count of its indirect dispatch, for at most
// countLimit texels (the capacity of a list whose counter may run past it). Past
// maxGroupsPerDimension groups along x they continue along y (linear_dispatch.glsl).
#include "shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = kDispatchBinding) buffer Dispatches { DispatchIndirect dispatches[]; };

uniform int levelCount;
uniform uint countLimit;
uniform uint maxGroupsPerDimension;

void main() {
  for (int level = 0; level < levelCount; ++level) {
    uint count = min(dispatches[level].texelCount, countLimit);
    uint groups = (count + uint(kGatherGroupSize) - 1u) / uint(kGatherGroupSize);
    uint rows = (groups + maxGroupsPerDimension - 1u) / maxGroupsPerDimension;
    dispatches[level].groupsX = rows == 0u ? 0u : (groups + rows - 1u) / rows;
    dispatches[level].groupsY = rows;
    dispatches[level].groupsZ = 1u;
  }
}
