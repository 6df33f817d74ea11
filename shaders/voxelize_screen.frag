#version 450 core
#extension GL_GOOGLE_include_directive : require
// Screen-grid voxelization (the paper's grid): the scene is rasterised at the grid's column
// resolution and each fragment marks the depth slice it falls in. Surface mode sets that voxel;
// solid mode flips every voxel from it to the end of the column (XOR), filling closed objects.
#include "shared.h"

layout(location = 0) in vec3 worldPosition;

layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };

uniform bool solidFill;

void main() {
  ivec2 column = ivec2(gl_FragCoord.xy);
  float depth = dot(worldPosition - grid.eyePosition.xyz, grid.viewForward.xyz);
  float slicePosition = (depth - grid.depthRange.x) / (grid.depthRange.y - grid.depthRange.x) *
                        float(grid.resolution.z);
  int slice = int(floor(solidFill ? slicePosition + 0.5 : slicePosition));
  if (slice < 0 || slice >= grid.resolution.z) return;
  uint base = uint((column.y * grid.resolution.x + column.x) * grid.resolution.w);
  if (!solidFill) {
    atomicOr(voxels[base + uint(slice / 32)], 1u << uint(slice % 32));
    return;
  }
  atomicXor(voxels[base + uint(slice / 32)], ~0u << uint(slice % 32));
  for (int word = slice / 32 + 1; word < grid.resolution.w; ++word)
    atomicXor(voxels[base + uint(word)], ~0u);
}
