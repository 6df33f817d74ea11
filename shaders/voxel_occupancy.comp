#version 450 core
#extension GL_GOOGLE_include_directive : require
// World-grid voxelization, after the transpose: one level of the occupancy pyramid that the
// clear-light test descends (voxel_grid.glsl, cellBounds). Level 1 sets a cell's bit when any of
// its 2x2x2 voxels is occupied, a word of a column at a time. Level 2 stores the box of the
// occupied voxels among its 4x4x4, read from the voxels themselves (level 1's cells would round
// it to whole pairs of voxels); a higher level the box of its 8 cells' boxes, or kEmptyCell. One
// thread per cell above level 1.
#include "shared.h"

layout(local_size_x = 64) in;

layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };

#include "light_pyramid.glsl"
#include "voxel_grid.glsl"
#include "linear_dispatch.glsl"

uniform int level;

// Level 1, one word of a column along z: 32 cells, each the OR of a pair of voxels along z in
// each of its 2x2 voxel columns, so 64 voxels of each, two of their words.
void buildLevelOne(ivec4 cells, int index) {
  int columnWords = occupancyColumnWords();
  if (index >= cells.x * cells.y * columnWords) return;
  int word = index % columnWords;
  ivec2 cell = ivec2((index / columnWords) % cells.x, index / (columnWords * cells.x));
  uint voxelRuns[2] = uint[2](0u, 0u);
  for (int column = 0; column < 4; ++column) {
    ivec2 xy = 2 * cell + ivec2(column & 1, column >> 1);
    if (any(greaterThanEqual(xy, grid.resolution.xy))) continue;
    for (int upper = 0; upper < 2; ++upper) {
      int voxelWord = 2 * word + upper;
      if (voxelWord < grid.resolution.w)
        voxelRuns[upper] |= voxels[columnStart(2, xy.x, xy.y) + uint(voxelWord)];
    }
  }
  uint bits = 0u;
  for (int bit = 0; bit < 32; ++bit) {
    if (((voxelRuns[bit / 16] >> uint(2 * (bit % 16))) & 3u) != 0u) bits |= 1u << uint(bit);
  }
  voxels[uint(cells.w + index)] = bits;
}

void main() {
  ivec4 cells = grid.occupancyLevels[level - 1];
  int index = int(linearInvocationIndex());
  if (level == 1) {
    buildLevelOne(cells, index);
    return;
  }
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
  } else {
    for (int child = 0; child < 8; ++child) {
      ivec3 childLow;
      ivec3 childHigh;
      if (cellBounds(level - 1, 2 * cell + ivec3(child & 1, (child >> 1) & 1, child >> 2),
                     childLow, childHigh)) {
        low = min(low, childLow);
        high = max(high, childHigh);
      }
    }
  }
  voxels[uint(cells.w + index)] = high.x >= 0 ? packCellBounds(level, cell, low, high) : kEmptyCell;
}
