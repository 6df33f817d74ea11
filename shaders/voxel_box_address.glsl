// Where the box of a voxel's surfaces lies (GpuVoxelGrid::occupancy): the first of its three words
// of slices in `voxels`, or kNoBrick when its cell has no brick. Needs the `grid` and `voxels`
// buffers declared before the include; voxelize_world.comp writes the words, voxel_grid.glsl
// reads them.
uint voxelBoxFirstWord(ivec3 voxel) {
  ivec4 cells = grid.occupancyLevels[kVoxelBrickLevel - 1];
  ivec3 cell = voxel >> kVoxelBrickLevel;
  uint brick = voxels[uint(grid.occupancy.y + (cell.z * cells.y + cell.y) * cells.x + cell.x)];
  if (brick == kNoBrick) return kNoBrick;
  int brickSide = 1 << kVoxelBrickLevel;
  ivec3 inBrick = voxel & (brickSide - 1);
  return uint(grid.occupancy.z) + brick * uint(kBrickWords) +
         3u * uint((inBrick.z * brickSide + inBrick.y) * brickSide + inBrick.x);
}
