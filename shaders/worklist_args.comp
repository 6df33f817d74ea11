#version 450 core
#extension GL_GOOGLE_include_directive : require
// Turns each level's texel count into the work-group count of its indirect gather dispatch.
#include "shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = kDispatchBinding) buffer Dispatches { DispatchIndirect dispatches[]; };

uniform int levelCount;

void main() {
  for (int level = 0; level < levelCount; ++level) {
    uint count = dispatches[level].texelCount;
    dispatches[level].groupsX = (count + uint(kGatherGroupSize) - 1u) / uint(kGatherGroupSize);
    dispatches[level].groupsY = 1u;
    dispatches[level].groupsZ = 1u;
  }
}
