#version 450 core
#extension GL_GOOGLE_include_directive : require
// Turns each level's texel count into the work-group count of its indirect dispatch, for at most
// countLimit texels (the capacity of a list whose counter may run past it).
#include "shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = kDispatchBinding) buffer Dispatches { DispatchIndirect dispatches[]; };

uniform int levelCount;
uniform uint countLimit;

void main() {
  for (int level = 0; level < levelCount; ++level) {
    uint count = min(dispatches[level].texelCount, countLimit);
    dispatches[level].groupsX = (count + uint(kGatherGroupSize) - 1u) / uint(kGatherGroupSize);
    dispatches[level].groupsY = 1u;
    dispatches[level].groupsZ = 1u;
  }
}
