#version 450 core
#extension GL_GOOGLE_include_directive : require
// World-grid voxelization, after the occupancy pyramid: hands each occupied cell of level
// kVoxelBrickLevel a brick of the pool, where the box pass of voxelize_world.comp marks the
// slices its voxels' surfaces cover (GpuVoxelGrid::occupancy). A cell past the pool's capacity
// gets kNoBrick; the count of bricks handed out tells voxelize.cpp to grow the pool and
// voxelize again. One thread per cell.
#include "shared.h"

layout(local_size_x = 64) in;

layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };

#include "linear_dispatch.glsl"

void main() {
  uint cell = linearInvocationIndex();
  ivec4 cells = grid.occupancyLevels[kVoxelBrickLevel - 1];
  if (cell >= uint(cells.x * cells.y * cells.z)) return;
  uint brick = kNoBrick;
  if (voxels[uint(cells.w) + cell] != kEmptyCell) {
    uint handedOut = atomicAdd(voxels[uint(grid.occupancy.y) - 1u], 1u);
    if (handedOut < uint(grid.occupancy.w)) brick = handedOut;
  }
  voxels[uint(grid.occupancy.y) + cell] = brick;
}
