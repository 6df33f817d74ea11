// The voxel grid and shadow-ray traversal. Needs the `grid` (GpuVoxelGrid) and `voxels`
// (uint words) buffers declared before the include.
//
// Layout of `voxels`: bit columns of 32-bit words. The first block holds columns along z, word
// (y * resolution.x + x) * resolution.w + z / 32; every grid has it. A world grid also holds the
// same voxels as columns along x and along y (voxelize.cpp writes them by transposing the first
// block), so that the exact traversal can read a run of voxels along the ray's main axis with
// one word instead of one voxel per step.

// Voxels per axis (xyz), and words per column along that axis.
ivec3 axisWordCounts() {
  return (grid.resolution.xyz + 31) / 32;
}

// First word of the column along `axis` through the voxel whose two other coordinates are
// (u, v) = (coordinate (axis + 1) % 3, coordinate (axis + 2) % 3).
uint columnStart(int axis, int u, int v) {
  ivec3 n = grid.resolution.xyz;
  ivec3 words = axisWordCounts();
  if (axis == 2) return uint((v * n.x + u) * grid.resolution.w);
  uint zBlock = uint(n.x * n.y * grid.resolution.w);
  if (axis == 0) return zBlock + uint((v * n.y + u) * words.x);
  return zBlock + uint(n.z * n.y * words.x) + uint((v * n.z + u) * words.y);
}

bool voxelOccupied(ivec3 voxel) {
  if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, grid.resolution.xyz)))
    return false;
  uint word = voxels[columnStart(2, voxel.x, voxel.y) + uint(voxel.z / 32)];
  return (word & (1u << uint(voxel.z % 32))) != 0u;
}

// Whether any voxel from `first` to `last` (inclusive, inside the grid) of a column is occupied.
bool runOccupied(int axis, int u, int v, int first, int last) {
  uint start = columnStart(axis, u, v);
  for (int word = first / 32; word <= last / 32; ++word) {
    int low = max(first - word * 32, 0);
    int high = min(last - word * 32, 31);
    uint mask = (~0u << uint(low)) & (~0u >> uint(31 - high));
    if ((voxels[start + uint(word)] & mask) != 0u) return true;
  }
  return false;
}

// Continuous grid coordinates of a world point: voxel v spans [v, v+1) on each axis. Points
// behind the camera of a screen grid map outside it.
vec3 gridCoordinates(vec3 world) {
  if (grid.modes.x == kGridWorld) return (world - grid.boundsMin.xyz) / grid.voxelSize.xyz;
  mat4 clipFromWorld = mat4(grid.clipFromWorld[0], grid.clipFromWorld[1], grid.clipFromWorld[2],
                            grid.clipFromWorld[3]);
  vec4 clip = clipFromWorld * vec4(world, 1.0);
  if (clip.w <= 0.0) return vec3(-1.0);
  vec2 column = (clip.xy / clip.w * 0.5 + 0.5) * vec2(grid.resolution.xy);
  float depth = dot(world - grid.eyePosition.xyz, grid.viewForward.xyz);
  float slice = (depth - grid.depthRange.x) / (grid.depthRange.y - grid.depthRange.x) *
                float(grid.resolution.z);
  return vec3(column, slice);
}

bool occupiedAt(vec3 world) {
  vec3 coordinates = gridCoordinates(world);
  if (grid.modes.w == 0) return voxelOccupied(ivec3(floor(coordinates)));
  // Widened ray: the 2x2x2 voxels nearest the point, so thin geometry between two samples
  // of the ray still stops it.
  ivec3 first = ivec3(floor(coordinates - 0.5));
  for (int i = 0; i < 8; ++i) {
    if (voxelOccupied(first + ivec3(i & 1, (i >> 1) & 1, i >> 2))) return true;
  }
  return false;
}

// Uniform stepping, as the thesis did: a fixed number of samples at the centres of equal
// parts of the segment.
bool segmentBlockedUniform(vec3 from, vec3 to) {
  int steps = grid.modes.z;
  for (int i = 0; i < steps; ++i) {
    if (occupiedAt(mix(from, to, (float(i) + 0.5) / float(steps)))) return true;
  }
  return false;
}

// Exact traversal of every voxel the segment passes through (world grid only): a 2D DDA over
// the columns along the segment's main axis, reading at each column the run of voxels the
// segment covers inside it. Equal to a 3D DDA's voxels, in |du| + |dv| steps instead of
// |du| + |dv| + |dmain|.
bool segmentBlockedDda(vec3 from, vec3 to) {
  vec3 start = gridCoordinates(from);
  vec3 direction = gridCoordinates(to) - start;
  // An axis the segment does not move along would give 0 * inf = NaN below.
  direction += vec3(equal(direction, vec3(0.0))) * 1e-7;
  // Clip the segment to the grid's box so the walk starts inside it.
  vec3 inverse = 1.0 / direction;
  vec3 toLow = -start * inverse;
  vec3 toHigh = (vec3(grid.resolution.xyz) - start) * inverse;
  float enter = max(max(min(toLow.x, toHigh.x), min(toLow.y, toHigh.y)),
                    max(min(toLow.z, toHigh.z), 0.0));
  float leave = min(min(max(toLow.x, toHigh.x), max(toLow.y, toHigh.y)),
                    min(max(toLow.z, toHigh.z), 1.0));
  if (enter >= leave) return false;

  vec3 magnitude = abs(direction);
  int axis = magnitude.x >= max(magnitude.y, magnitude.z) ? 0 : (magnitude.y >= magnitude.z ? 1 : 2);
  int uAxis = (axis + 1) % 3;
  int vAxis = (axis + 2) % 3;
  int length = grid.resolution[axis];
  ivec2 size = ivec2(grid.resolution[uAxis], grid.resolution[vAxis]);
  vec2 across = vec2(direction[uAxis], direction[vAxis]);
  vec2 acrossStart = vec2(start[uAxis], start[vAxis]);
  vec2 acrossInverse = vec2(inverse[uAxis], inverse[vAxis]);

  ivec2 column = clamp(ivec2(floor(acrossStart + across * enter)), ivec2(0), size - 1);
  ivec2 stepDirection = ivec2(sign(across));
  vec2 tMax = (vec2(column) + max(vec2(stepDirection), vec2(0.0)) - acrossStart) * acrossInverse;
  vec2 tDelta = abs(acrossInverse);
  float runStart = enter;
  for (int i = 0; i < size.x + size.y + 2; ++i) {
    float runEnd = min(min(tMax.x, tMax.y), leave);
    float first = start[axis] + direction[axis] * runStart;
    float last = start[axis] + direction[axis] * runEnd;
    int low = clamp(int(floor(min(first, last))), 0, length - 1);
    int high = clamp(int(floor(max(first, last))), 0, length - 1);
    if (runOccupied(axis, column.x, column.y, low, high)) return true;
    if (runEnd >= leave) return false;
    if (tMax.x < tMax.y) {
      column.x += stepDirection.x;
      tMax.x += tDelta.x;
    } else {
      column.y += stepDirection.y;
      tMax.y += tDelta.y;
    }
    runStart = runEnd;
  }
  return false;
}

bool segmentBlocked(vec3 from, vec3 to) {
  return grid.modes.y == kTraversalDda ? segmentBlockedDda(from, to)
                                       : segmentBlockedUniform(from, to);
}

// How far a shadow ray's end moves off a surface with unit normal `normal`: the origin offset
// times the thickness of the layer of voxels that a plane with this normal marks (its voxels
// reach dot(|normal|, voxel size) from it), so the ray starts outside its own surface's voxels
// and, moving away from the plane, never enters them again. A screen grid's voxels vary in
// size; it uses the diagonal of a voxel at mid depth.
float surfaceOffset(vec3 normal) {
  float layer = grid.modes.x == kGridWorld ? dot(abs(normal), grid.voxelSize.xyz)
                                           : grid.voxelSize.w;
  return grid.boundsMin.w * layer;
}

// Whether a VPL (at vplPosition, emitting along vplNormal) is visible from a surface point.
// Both ends move off their surfaces along the surfaces' normals (surfaceOffset), so that neither
// the point's own surface nor the light's quad (or a ceiling it is set in) shadows the ray.
bool vplVisible(vec3 position, vec3 normal, vec3 vplPosition, vec3 vplNormal) {
  vec3 from = position + normal * surfaceOffset(normal);
  vec3 to = vplPosition + vplNormal * surfaceOffset(vplNormal);
  // Ends that moved past each other (a point almost touching the light) see it.
  if (dot(to - from, vplPosition - position) <= 0.0) return true;
  return !segmentBlocked(from, to);
}
