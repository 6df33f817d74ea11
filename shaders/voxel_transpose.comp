#version 450 core
#extension GL_GOOGLE_include_directive : require
// World-grid voxelization, last step: copies the columns along z, where voxelize_world.comp
// marks the voxels, into the columns along x (axis 0) or y (axis 1) that the exact traversal
// reads (voxel_grid.glsl). One thread per word of the target columns.
#include "shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = kVoxelGridBinding) readonly buffer Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };

#include "light_pyramid.glsl"
#include "voxel_grid.glsl"
#include "linear_dispatch.glsl"

uniform int axis;

void main() {
  int uAxis = (axis + 1) % 3;
  int vAxis = (axis + 2) % 3;
  ivec3 size = grid.resolution.xyz;
  int wordsPerColumn = axisWordCounts()[axis];
  int index = int(linearInvocationIndex());
  if (index >= size[uAxis] * size[vAxis] * wordsPerColumn) return;
  int word = index % wordsPerColumn;
  int column = index / wordsPerColumn;
  ivec3 voxel;
  voxel[uAxis] = column % size[uAxis];
  voxel[vAxis] = column / size[uAxis];
  uint bits = 0u;
  for (int bit = 0; bit < 32; ++bit) {
    voxel[axis] = word * 32 + bit;
    if (voxel[axis] >= size[axis]) break;
    if (voxelOccupied(voxel)) bits |= 1u << uint(bit);
  }
  voxels[columnStart(axis, voxel[uAxis], voxel[vAxis]) + uint(word)] = bits;
}
