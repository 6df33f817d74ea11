// The voxel grid and shadow-ray traversal. Needs the `grid` (GpuVoxelGrid) and `voxels`
// (uint words) buffers declared before the include.

bool voxelOccupied(ivec3 voxel) {
  if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, grid.resolution.xyz)))
    return false;
  uint word = voxels[(voxel.y * grid.resolution.x + voxel.x) * grid.resolution.w + voxel.z / 32];
  return (word & (1u << uint(voxel.z % 32))) != 0u;
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

// Exact traversal (3D DDA) of every voxel the segment passes through, world grid only.
bool segmentBlockedDda(vec3 from, vec3 to) {
  vec3 start = gridCoordinates(from);
  vec3 end = gridCoordinates(to);
  vec3 direction = end - start;
  // An axis the segment does not move along would give 0 * inf = NaN below.
  direction += vec3(equal(direction, vec3(0.0))) * 1e-7;
  // Clip the segment to the grid's box so the walk starts inside it.
  vec3 inverse = 1.0 / direction;
  vec3 toLow = (vec3(0.0) - start) * inverse;
  vec3 toHigh = (vec3(grid.resolution.xyz) - start) * inverse;
  float enter = max(max(min(toLow.x, toHigh.x), min(toLow.y, toHigh.y)),
                    max(min(toLow.z, toHigh.z), 0.0));
  float leave = min(min(max(toLow.x, toHigh.x), max(toLow.y, toHigh.y)),
                    min(max(toLow.z, toHigh.z), 1.0));
  if (enter >= leave) return false;
  vec3 position = start + direction * enter;
  ivec3 voxel = clamp(ivec3(floor(position)), ivec3(0), grid.resolution.xyz - 1);
  ivec3 stepDirection = ivec3(sign(direction));
  vec3 nextBoundary = vec3(voxel) + max(vec3(stepDirection), vec3(0.0));
  vec3 tMax = (nextBoundary - start) * inverse;
  vec3 tDelta = abs(inverse);
  for (int i = 0; i < 4 * 4096; ++i) {
    if (voxelOccupied(voxel)) return true;
    float next = min(min(tMax.x, tMax.y), tMax.z);
    if (next > leave) return false;
    if (tMax.x == next) {
      voxel.x += stepDirection.x;
      tMax.x += tDelta.x;
    } else if (tMax.y == next) {
      voxel.y += stepDirection.y;
      tMax.y += tDelta.y;
    } else {
      voxel.z += stepDirection.z;
      tMax.z += tDelta.z;
    }
  }
  return false;
}

// Whether a VPL is visible from a surface point. Both ends move off their surfaces by the
// origin offset (in voxel diagonals), so that a surface does not shadow itself through the
// voxels it occupies, nor the light through its own.
bool vplVisible(vec3 position, vec3 normal, vec3 vplPosition) {
  float offset = grid.boundsMin.w * grid.voxelSize.w;
  vec3 towardsLight = vplPosition - position;
  float distanceToLight = length(towardsLight);
  if (distanceToLight <= 2.0 * offset) return true;
  vec3 direction = towardsLight / distanceToLight;
  vec3 from = position + normal * offset;
  vec3 to = vplPosition - direction * offset;
  bool blocked = grid.modes.y == kTraversalDda ? segmentBlockedDda(from, to)
                                               : segmentBlockedUniform(from, to);
  return !blocked;
}
