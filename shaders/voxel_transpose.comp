#version 450 core
#extension GL_GOOGLE_include_directive : require
// World-grid voxelization, last step: copies the columns along z, where voxelize_world.comp
// marks the voxels, into the columns along x (axis 0) or y (axis 1) that the exact traversal
// reads (voxel_grid.glsl).
//
// One thread per tile of 32 x 32 voxels in a plane of constant y (axis 0) or x (axis 1): word w'
// of 32 columns along z that lie side by side along the axis is a 32 x 32 bit matrix (row i,
// bit j: the voxel at 32 w + i along the axis and 32 w' + j along z), whose transpose is word w
// of the 32 target columns through those 32 voxels of z. Transposed in registers, the tile takes
// 32 loads for 32 words; a word built bit by bit from the columns along z took 32 loads for one,
// and at 512^3 that was two thirds of the voxelization's time.
#include "shared.h"

layout(local_size_x = 64) in;

layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };

#include "light_pyramid.glsl"
#include "voxel_grid.glsl"
#include "linear_dispatch.glsl"

uniform int axis;

void main() {
  ivec3 size = grid.resolution.xyz;
  int zWords = grid.resolution.w;
  int axisWords = axisWordCounts()[axis];
  // The coordinate that is neither the axis nor z: y for axis 0, x for axis 1.
  int planeAxis = 1 - axis;
  int index = int(linearInvocationIndex());
  if (index >= size[planeAxis] * zWords * axisWords) return;
  int axisWord = index % axisWords;
  int zWord = (index / axisWords) % zWords;
  int plane = index / (axisWords * zWords);

  uint rows[32];
  ivec3 voxel;
  voxel[planeAxis] = plane;
  for (int i = 0; i < 32; ++i) {
    voxel[axis] = axisWord * 32 + i;
    rows[i] = voxel[axis] < size[axis] ? voxels[columnStart(2, voxel.x, voxel.y) + uint(zWord)]
                                       : 0u;
  }
  // Swaps the off-diagonal blocks of every 2j x 2j block, from j = 16 down to 1: bits j to
  // 2j - 1 of row k against bits 0 to j - 1 of row k + j, in each group of 2j bits.
  uint lowBits = 0x0000ffffu;
  for (int j = 16; j > 0; j >>= 1, lowBits ^= lowBits << uint(j)) {
    for (int k = 0; k < 32; k = (k + j + 1) & ~j) {
      uint swapped = ((rows[k] >> uint(j)) ^ rows[k + j]) & lowBits;
      rows[k] ^= swapped << uint(j);
      rows[k + j] ^= swapped;
    }
  }
  // A world grid's z resolution is whole words (voxelize.cpp), so every row is a target word.
  for (int j = 0; j < 32; ++j) {
    int z = zWord * 32 + j;
    ivec2 across = axis == 0 ? ivec2(plane, z) : ivec2(z, plane);
    voxels[columnStart(axis, across.x, across.y) + uint(axisWord)] = rows[j];
  }
}
