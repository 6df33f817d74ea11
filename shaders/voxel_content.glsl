// What a voxel's brick holds about the surfaces inside it (GpuVoxelGrid::occupancy): where its
// kVoxelContentWords words lie, and how a plane word's normal is coded. Needs the `grid` and
// `voxels` buffers declared before the include; voxelize_world.comp writes the words,
// voxel_grid.glsl reads them.

// The first of the voxel's words in `voxels` (three of box slices, then two plane words), or
// kNoBrick when its cell has no brick.
uint voxelContentFirstWord(ivec3 voxel) {
  ivec4 cells = grid.occupancyLevels[kVoxelBrickLevel - 1];
  ivec3 cell = voxel >> kVoxelBrickLevel;
  uint brick = voxels[uint(grid.occupancy.y + (cell.z * cells.y + cell.y) * cells.x + cell.x)];
  if (brick == kNoBrick) return kNoBrick;
  int brickSide = 1 << kVoxelBrickLevel;
  ivec3 inBrick = voxel & (brickSide - 1);
  return uint(grid.occupancy.z) + brick * uint(kBrickWords) +
         uint(kVoxelContentWords * ((inBrick.z * brickSide + inBrick.y) * brickSide + inBrick.x));
}

// A plane's unit normal as 16 bits: its octahedral coordinates u, v (of the normal turned to
// z >= 0, since a slab does not care for the side) on 255 steps each, so that the axes and 0 code
// exactly.
uint encodePlaneNormal(vec3 normal) {
  if (normal.z < 0.0) normal = -normal;
  vec2 octahedral = normal.xy / (abs(normal.x) + abs(normal.y) + normal.z);
  uvec2 code = uvec2(round(clamp(octahedral, -1.0, 1.0) * 127.0 + 127.0));
  return code.x | code.y << 8;
}

vec3 decodePlaneNormal(uint code) {
  vec2 octahedral = (vec2(code & 255u, (code >> 8) & 255u) - 127.0) / 127.0;
  return normalize(
      vec3(octahedral, max(1.0 - abs(octahedral.x) - abs(octahedral.y), 0.0)));
}
