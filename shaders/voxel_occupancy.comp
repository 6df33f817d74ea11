#version 450 core
#extension GL_GOOGLE_include_directive : require
// World-grid voxelization, after the transpose: one level of the occupancy pyramid that the
// clear-light test descends (voxel_grid.glsl, cellBounds). Level 1 sets a cell's bit when any of
// its 2x2x2 voxels is occupied (the grid's words start cleared). Level 2 stores the box of the
// occupied voxels among its 4x4x4, read from the voxels themselves (level 1's cells would round
// it to whole pairs of voxels); a higher level the box of its 8 cells' boxes, or kEmptyCell. One
// thread per cell.
#include "shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = kVoxelGridBinding) readonly buffer Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };

#include "voxel_grid.glsl"

uniform int level;

void main() {
  ivec4 cells = grid.occupancyLevels[level - 1];
  int index = int(gl_GlobalInvocationID.x);
  if (index >= cells.x * cells.y * cells.z) return;
  ivec3 cell = ivec3(index % cells.x, (index / cells.x) % cells.y, index / (cells.x * cells.y));
  ivec3 low = ivec3(0x7fffffff);
  ivec3 high = ivec3(-1);
  if (level == 2) {
    // Four voxels of a column along z share a word (grid.resolution.z is a multiple of 32).
    for (int column = 0; column < 16; ++column) {
      ivec2 xy = 4 * cell.xy + ivec2(column % 4, column / 4);
      if (any(greaterThanEqual(xy, grid.resolution.xy))) continue;
      int z = 4 * cell.z;
      uint run = (voxels[columnStart(2, xy.x, xy.y) + uint(z / 32)] >> uint(z % 32)) & 15u;
      if (run == 0u) continue;
      low = min(low, ivec3(xy, z + findLSB(run)));
      high = max(high, ivec3(xy + 1, z + findMSB(run) + 1));
    }
  }
  for (int child = 0; child < 8 && level != 2; ++child) {
    ivec3 childLow;
    ivec3 childHigh;
    if (cellBounds(level - 1, 2 * cell + ivec3(child & 1, (child >> 1) & 1, child >> 2),
                   childLow, childHigh)) {
      low = min(low, childLow);
      high = max(high, childHigh);
    }
  }
  bool occupied = high.x >= 0;
  if (level == 1) {
    if (occupied) atomicOr(voxels[uint(cells.w + index / 32)], 1u << uint(index % 32));
  } else {
    voxels[uint(cells.w + index)] = occupied ? packCellBounds(level, cell, low, high) : kEmptyCell;
  }
}
