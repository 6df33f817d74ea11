// The voxel grid and shadow-ray traversal. Needs the `grid` (GpuVoxelGrid) and `voxels`
// (uint words) buffers declared, and light_pyramid.glsl included, before the include.
//
// Layout of `voxels`: bit columns of 32-bit words. The first block holds columns along z, word
// (y * resolution.x + x) * resolution.w + z / 32; every grid has it. A world grid also holds the
// same voxels as columns along x and along y (voxelize.cpp writes them by transposing the first
// block), so that the exact traversal can read a run of voxels along the ray's main axis with
// one word instead of one voxel per step.

// The grid's modes (GpuVoxelGrid::modes, and whether its voxels hold boxes). A program compiled
// with PENUMBRA_DEFAULT_VOXEL_GRID defined serves only the default grid, a world grid walked
// exactly, not widened, with boxes inside its voxels (ShadowRayProgram picks it,
// src/render/shadow_rays.h): there they are constants, so that the other modes' code is left out.
// llvmpipe pays for code a program holds even where no thread runs it: without the other modes'
// code the frame with shadows took about an eighth less on the demo and the dragon
// (docs/shadows.md, "Programs for the default grid").
#ifdef PENUMBRA_DEFAULT_VOXEL_GRID
bool worldGrid() { return true; }
bool exactTraversal() { return true; }
bool widenedRays() { return false; }
bool boxesInVoxels() { return true; }
bool emptySpaceSkipping() { return true; }  // the boxes' bricks need a pyramid of two levels
#else
bool worldGrid() { return grid.modes.x == kGridWorld; }
bool exactTraversal() { return grid.modes.y == kTraversalDda; }
bool widenedRays() { return grid.modes.w != 0; }
bool boxesInVoxels() { return grid.occupancy.y != 0; }
// Whether the traversal skips empty space through the occupancy pyramid (skippingLevel): a cell
// holds a box from level 2 on.
bool emptySpaceSkipping() { return grid.occupancy.x >= 2; }
#endif

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

#include "voxel_content.glsl"

// The surfaces inside an occupied voxel, in grid coordinates, as voxelize_world.comp's box pass
// left them in the voxel's brick (GpuVoxelGrid::occupancy): the box of the slices they cover, and
// within it the slabs around its two planes (contentInterval reads them only where a segment meets
// the box). The whole voxel, and no slabs, where the grid has no boxes, where the brick pool ran
// out, or where no surface marked a slice (the inside of a solid fill).
struct VoxelContent {
  vec3 low;
  vec3 high;
  uint planeWords;  // the first of the two plane words, or kNoBrick without slabs
};

VoxelContent voxelContent(ivec3 voxel) {
  VoxelContent content;
  content.low = vec3(voxel);
  content.high = content.low + 1.0;
  content.planeWords = kNoBrick;
  if (!boxesInVoxels()) return content;
  uint first = voxelContentFirstWord(voxel);
  if (first == kNoBrick) return content;
  uvec3 slices = uvec3(voxels[first], voxels[first + 1u], voxels[first + 2u]);
  if (any(equal(slices, uvec3(0u)))) return content;
  content.low += vec3(findLSB(slices)) / float(kVoxelBoxSlices);
  content.high = vec3(voxel) + vec3(findMSB(slices) + 1) / float(kVoxelBoxSlices);
  content.planeWords = first + 3u;
  return content;
}

// One of the two slabs of a voxel's content: low <= dot(normal, point - centre) <= high.
struct VoxelSlab {
  vec3 normal;
  vec3 centre;
  float low;
  float high;
};

VoxelSlab voxelSlab(VoxelContent content, uint i) {
  uint word = voxels[content.planeWords + i];
  VoxelSlab slab;
  slab.normal = decodePlaneNormal(i == 0u ? word >> 16 : 0xffffu - (word >> 16));
  slab.centre = floor(content.low) + 0.5;
  float sliceSize = dot(abs(slab.normal), vec3(1.0)) / float(kVoxelPlaneSlices);
  uint slices = word & 0xffffu;
  slab.low = (float(findLSB(slices)) - 0.5 * float(kVoxelPlaneSlices)) * sliceSize;
  slab.high = (float(findMSB(slices)) + 1.0 - 0.5 * float(kVoxelPlaneSlices)) * sliceSize;
  return slab;
}

// Voxels by which the traversal grows the surfaces inside the voxels: more than the rounding of
// its tests, far less than a slice.
const float kVoxelBoxMargin = 1e-3;

// `inside` (a part of a segment, t from x to y) narrowed to the part within one of a content's
// slabs (grown by `margin`). A call per slab rather than a loop over the two: on llvmpipe the
// loop made the visibility passes several per cent slower (docs/shadows.md, "Fewer loops in the
// traversal").
vec2 slabInterval(vec2 inside, VoxelSlab slab, vec3 start, vec3 direction, float margin) {
  float startHeight = dot(slab.normal, start - slab.centre);
  float rise = dot(slab.normal, direction);
  float low = slab.low - margin - startHeight;
  float high = slab.high + margin - startHeight;
  if (abs(rise) < 1e-12) return low > 0.0 || high < 0.0 ? vec2(1.0, 0.0) : inside;
  float toLowSide = low / rise;
  float toHighSide = high / rise;
  return vec2(max(inside.x, min(toLowSide, toHighSide)), min(inside.y, max(toLowSide, toHighSide)));
}

// The part of the segment start + t direction, t from enter to leave, inside a voxel's content
// (grown by `margin`: its box and both slabs): t from x to y, none when x > y.
vec2 contentInterval(vec3 start, vec3 direction, vec3 inverse, float enter, float leave,
                     VoxelContent content, float margin) {
  vec3 toLow = (content.low - margin - start) * inverse;
  vec3 toHigh = (content.high + margin - start) * inverse;
  vec3 near = min(toLow, toHigh);
  vec3 far = max(toLow, toHigh);
  vec2 inside = vec2(max(max(near.x, near.y), max(near.z, enter)),
                     min(min(far.x, far.y), min(far.z, leave)));
  if (inside.x > inside.y || content.planeWords == kNoBrick) return inside;
  inside = slabInterval(inside, voxelSlab(content, 0u), start, direction, margin);
  return slabInterval(inside, voxelSlab(content, 1u), start, direction, margin);
}

bool segmentMeetsContent(vec3 start, vec3 direction, vec3 inverse, float enter, float leave,
                         VoxelContent content, float margin) {
  vec2 inside = contentInterval(start, direction, inverse, enter, leave, content, margin);
  return inside.x <= inside.y;
}

// Words per column along z of the occupancy pyramid's level 1.
int occupancyColumnWords() {
  return (grid.occupancyLevels[0].z + 31) / 32;
}

// A cell of the occupancy pyramid (GpuVoxelGrid::occupancy): level 0 is the voxels themselves,
// level k a cell of 2^k voxels per side. From level 2 on, its word holds the box of its occupied
// voxels, each bound 5 bits, in units of max(1, 2^(k-5)) voxels from the cell's first voxel
// (rounded outwards where a unit is more than a voxel): min x, y, z in bits 0 to 14, max x, y, z
// in 15 to 29. A box far smaller than its cell (a wall's layer of voxels, a light's quad) lets
// the clear-light test pass a cell that a plain occupied bit would make it descend into. Level 1
// holds a bit per cell (its box is the whole cell), in columns along z laid out as the voxels'
// (word (y * cells x + x) * occupancyColumnWords() + z / 32): a word per 8 voxels would take more
// memory than the voxels' three copies, and the columns let it be built a word at a time.
int cellBoundsUnit(int level) {
  return 1 << max(level - 5, 0);
}

uint packCellBounds(int level, ivec3 cell, ivec3 low, ivec3 high) {
  int unit = cellBoundsUnit(level);
  ivec3 origin = cell << level;
  ivec3 first = clamp((low - origin) / unit, 0, 31);
  ivec3 last = clamp((high - origin + unit - 1) / unit - 1, 0, 31);
  return uint(first.x | first.y << 5 | first.z << 10 | last.x << 15 | last.y << 20 | last.z << 25);
}

// Whether a cell holds an occupied voxel, and if so the box of them: voxels low to high - 1.
// Outside the grid, none.
bool cellBounds(int level, ivec3 cell, out ivec3 low, out ivec3 high) {
  low = cell;
  high = cell + 1;
  if (level == 0) return voxelOccupied(cell);
  ivec4 cells = grid.occupancyLevels[level - 1];
  if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, cells.xyz))) return false;
  if (level == 1) {
    low = cell << 1;
    high = low + 2;
    uint column = uint((cell.y * cells.x + cell.x) * occupancyColumnWords() + cell.z / 32);
    return (voxels[uint(cells.w) + column] & (1u << uint(cell.z % 32))) != 0u;
  }
  uint word = voxels[uint(cells.w + (cell.z * cells.y + cell.y) * cells.x + cell.x)];
  if (word == kEmptyCell) return false;
  int unit = cellBoundsUnit(level);
  ivec3 origin = cell << level;
  ivec3 first = ivec3(word, word >> 5, word >> 10) & 31;
  ivec3 last = ivec3(word >> 15, word >> 20, word >> 25) & 31;
  low = origin + first * unit;
  high = origin + (last + 1) * unit;
  return true;
}

// Continuous grid coordinates of a world point: voxel v spans [v, v+1) on each axis. Points
// behind the camera of a screen grid map outside it.
vec3 gridCoordinates(vec3 world) {
  if (worldGrid()) return (world - grid.boundsMin.xyz) / grid.voxelSize.xyz;
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
  if (!widenedRays()) return voxelOccupied(ivec3(floor(coordinates)));
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

// Voxels by which the boxes of occupied voxels grow in the tests against them (the traversal's
// empty-space skipping and the clear-light test): more than the traversal's rounding, so that
// neither skips a voxel the column walk would read.
const float kOccupiedBoxMargin = 0.01;

// A segment in grid coordinates, start + t direction, clipped to the grid's box: t from enter
// to leave. `inverse` is 1 / direction.
struct GridSegment {
  vec3 start;
  vec3 direction;
  vec3 inverse;
  float enter;
  float leave;
};

// The segment from `from` to `to` (world grid), clipped; false when it misses the grid.
bool clipToGrid(vec3 from, vec3 to, out GridSegment segment) {
  segment.start = gridCoordinates(from);
  // An axis the segment does not move along would give 0 * inf = NaN below.
  segment.direction = gridCoordinates(to) - segment.start;
  segment.direction += vec3(equal(segment.direction, vec3(0.0))) * 1e-7;
  segment.inverse = 1.0 / segment.direction;
  vec3 toLow = -segment.start * segment.inverse;
  vec3 toHigh = (vec3(grid.resolution.xyz) - segment.start) * segment.inverse;
  segment.enter = max(max(min(toLow.x, toHigh.x), min(toLow.y, toHigh.y)),
                      max(min(toLow.z, toHigh.z), 0.0));
  segment.leave = min(min(max(toLow.x, toHigh.x), max(toLow.y, toHigh.y)),
                      min(max(toLow.z, toHigh.z), 1.0));
  return segment.enter < segment.leave;
}

// Word `word` of the column whose first word is `start`, with only the bits of the run `first` to
// `last` (inclusive, inside the grid) kept.
uint runWord(uint start, int first, int last, int word) {
  int low = max(first - word * 32, 0);
  int high = min(last - word * 32, 31);
  return voxels[start + uint(word)] & (~0u << uint(low)) & (~0u >> uint(31 - high));
}

// Whether that run holds an occupied voxel. Most runs lie in one word, read before the loop:
// llvmpipe pays for each loop's iterations, masked or not (docs/shadows.md, "Fewer loops in the
// traversal").
bool runOccupied(uint start, int first, int last) {
  uint occupied = runWord(start, first, last, first / 32);
  for (int word = first / 32 + 1; word <= last / 32; ++word)
    occupied |= runWord(start, first, last, word);
  return occupied != 0u;
}

// Whether the segment, from t = enter to leave, meets an occupied voxel of the run `first` to
// `last` (inclusive, inside the grid) along `axis` in the column (u, v) = `column`, whose first
// word is `start`: with boxes where it meets the voxel's content (voxelContent), without them
// anywhere. The occupied voxels are found a word at a time, by their bits: a steep segment's run
// spans dozens of voxels. One loop over the words and their bits, not a loop over the bits inside
// one over the words (docs/shadows.md, "Fewer loops in the traversal").
bool runBlocked(GridSegment segment, int axis, ivec2 column, uint start, int first, int last,
                float enter, float leave) {
  if (!boxesInVoxels()) return runOccupied(start, first, last);
  ivec3 voxel;
  voxel[(axis + 1) % 3] = column.x;
  voxel[(axis + 2) % 3] = column.y;
  int word = first / 32;
  uint occupied = runWord(start, first, last, word);
  while (true) {
    if (occupied == 0u) {
      if (++word > last / 32) return false;
      occupied = runWord(start, first, last, word);
      continue;
    }
    int bit = findLSB(occupied);
    occupied &= occupied - 1u;
    voxel[axis] = word * 32 + bit;
    if (segmentMeetsContent(segment.start, segment.direction, segment.inverse, enter, leave,
                            voxelContent(voxel), kVoxelBoxMargin))
      return true;
  }
}

// A 2D DDA's state over the columns along a segment's main axis (columnsBlocked).
struct ColumnStep {
  ivec2 column;
  int columnWord;  // the column's first word
  vec2 tMax;       // t at which the segment leaves the column along u and along v
  ivec2 direction;
  ivec2 wordStep;  // words between neighbouring columns along u and along v
  vec2 tDelta;
};

void nextColumn(inout ColumnStep walk) {
  if (walk.tMax.x < walk.tMax.y) {
    walk.columnWord += walk.wordStep.x;
    walk.column.x += walk.direction.x;
    walk.tMax.x += walk.tDelta.x;
  } else {
    walk.columnWord += walk.wordStep.y;
    walk.column.y += walk.direction.y;
    walk.tMax.y += walk.tDelta.y;
  }
}

// The exact traversal's walk over the segment from t = enter to t = leave: a 2D DDA over the
// columns along the segment's main axis, reading at each column the run of voxels the segment
// covers inside it. Equal to a 3D DDA's voxels, in |du| + |dv| steps instead of
// |du| + |dv| + |dmain|. A run with occupied voxels blocks the segment where it meets the content
// of one of them (runBlocked).
//
// Two loops: the inner steps over columns until a run holds an occupied voxel, the outer tests
// their contents. llvmpipe runs neighbouring threads in SIMD lanes and runs the code of every
// branch and loop for all of them, masked, even where no lane takes it: inside the step loop, the
// contents' test cost every step of every ray (80% of the dragon's tracing).
bool columnsBlocked(GridSegment segment, float enter, float leave) {
  vec3 start = segment.start;
  vec3 direction = segment.direction;
  vec3 magnitude = abs(direction);
  int axis = magnitude.x >= max(magnitude.y, magnitude.z) ? 0 : (magnitude.y >= magnitude.z ? 1 : 2);
  int uAxis = (axis + 1) % 3;
  int vAxis = (axis + 2) % 3;
  int length = grid.resolution[axis];
  ivec2 size = ivec2(grid.resolution[uAxis], grid.resolution[vAxis]);
  vec2 across = vec2(direction[uAxis], direction[vAxis]);
  vec2 acrossStart = vec2(start[uAxis], start[vAxis]);
  vec2 acrossInverse = vec2(segment.inverse[uAxis], segment.inverse[vAxis]);

  ColumnStep walk;
  walk.column = clamp(ivec2(floor(acrossStart + across * enter)), ivec2(0), size - 1);
  walk.direction = ivec2(sign(across));
  int wordsPerColumn = axis == 2 ? grid.resolution.w : axisWordCounts()[axis];
  walk.wordStep = walk.direction * ivec2(wordsPerColumn, size.x * wordsPerColumn);
  walk.columnWord = int(columnStart(axis, walk.column.x, walk.column.y));
  walk.tMax = (vec2(walk.column) + max(vec2(walk.direction), vec2(0.0)) - acrossStart) *
              acrossInverse;
  walk.tDelta = abs(acrossInverse);
  float runStart = enter;
  int steps = size.x + size.y + 2;
  for (int i = 0; i < steps; ++i) {
    float runEnd;
    int low;
    int high;
    bool occupied = false;
    for (; i < steps; ++i) {
      runEnd = min(min(walk.tMax.x, walk.tMax.y), leave);
      float first = start[axis] + direction[axis] * runStart;
      float last = start[axis] + direction[axis] * runEnd;
      low = clamp(int(floor(min(first, last))), 0, length - 1);
      high = clamp(int(floor(max(first, last))), 0, length - 1);
      occupied = runOccupied(uint(walk.columnWord), low, high);
      if (occupied) break;
      if (runEnd >= leave) return false;
      nextColumn(walk);
      runStart = runEnd;
    }
    if (!occupied) return false;
    if (runBlocked(segment, axis, walk.column, uint(walk.columnWord), low, high, enter, leave))
      return true;
    if (runEnd >= leave) return false;
    nextColumn(walk);
    runStart = runEnd;
  }
  return false;
}

// The occupancy level whose cells the traversal skips when the segment misses their occupied
// voxels (where emptySpaceSkipping): cells of 32^3 voxels (measured on the demo and the dragon at
// 8^3 to 64^3: finer cells cost more steps than they spare columns, nested levels gained
// nothing), or the coarsest level of a smaller pyramid.
int skippingLevel() {
  return min(grid.occupancy.x, 5);
}

// The 3D DDA's step to the next cell along the segment; false when the segment ends in this one.
bool nextCell(inout ivec3 cell, inout vec3 tMax, ivec3 stepDirection, vec3 tDelta, float leave) {
  if (min(min(tMax.x, tMax.y), tMax.z) >= leave) return false;
  if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
    cell.x += stepDirection.x;
    tMax.x += tDelta.x;
  } else if (tMax.y <= tMax.z) {
    cell.y += stepDirection.y;
    tMax.y += tDelta.y;
  } else {
    cell.z += stepDirection.z;
    tMax.z += tDelta.z;
  }
  return true;
}

// Empty-space skipping: a 3D DDA over the cells of occupancy level `level` that the segment
// passes through, walking the columns only over the part of the segment inside the box of a
// cell's occupied voxels. Every occupied voxel the segment passes through lies in such a box,
// so the answer is the column walk's over the whole segment; in an open room a shadow ray
// walks the columns near its ends and next to occluders only.
bool cellsBlocked(GridSegment segment, int level) {
  vec3 start = segment.start;
  vec3 direction = segment.direction;
  float cellSize = float(1 << level);
  ivec3 cells = grid.occupancyLevels[level - 1].xyz;
  ivec3 cell = clamp(ivec3(floor((start + direction * segment.enter) / cellSize)), ivec3(0),
                     cells - 1);
  ivec3 stepDirection = ivec3(sign(direction));
  vec3 tMax = ((vec3(cell) + max(vec3(stepDirection), vec3(0.0))) * cellSize - start) *
              segment.inverse;
  vec3 tDelta = abs(segment.inverse) * cellSize;
  int steps = cells.x + cells.y + cells.z + 3;
  // As in columnsBlocked, the inner loop steps over cells until the segment meets a cell's box of
  // occupied voxels, and the outer walks the columns there.
  for (int i = 0; i < steps; ++i) {
    float boxEnter;
    float boxLeave;
    bool meets = false;
    for (; i < steps; ++i) {
      ivec3 occupiedLow;
      ivec3 occupiedHigh;
      if (cellBounds(level, cell, occupiedLow, occupiedHigh)) {
        vec3 toLow = (vec3(occupiedLow) - kOccupiedBoxMargin - start) * segment.inverse;
        vec3 toHigh = (vec3(occupiedHigh) + kOccupiedBoxMargin - start) * segment.inverse;
        vec3 near = min(toLow, toHigh);
        vec3 far = max(toLow, toHigh);
        boxEnter = max(max(near.x, near.y), max(near.z, segment.enter));
        boxLeave = min(min(far.x, far.y), min(far.z, segment.leave));
        meets = boxEnter <= boxLeave;
      }
      if (meets) break;
      if (!nextCell(cell, tMax, stepDirection, tDelta, segment.leave)) return false;
    }
    if (!meets) return false;
    if (columnsBlocked(segment, boxEnter, boxLeave)) return true;
    if (!nextCell(cell, tMax, stepDirection, tDelta, segment.leave)) return false;
  }
  return false;
}

// Most voxel contents a segment leaves at its start: at an inner corner a point may start in the
// contents of two perpendicular surfaces, and a curved surface's content continues into the next
// voxel (measured with 1 to 3 on five shadow scenes: 1 left dark seams along the light near the
// wall's corners, 3 let the resting bunny's chest see the light through its head).
const int kStartContentsLeft = 2;

// Moves the enter of a segment that starts inside the grid out of the voxel contents (voxelContent)
// it starts in; false when it is still inside one after kStartContentsLeft of them (or ends
// first), which blocks it. The start lies off its own surface by surfaceOffset, but a point next
// to another surface may start inside that surface's content, and on a curved or slanted surface
// inside its own (whose slabs hold the whole curve inside the voxel): every ray of the point would
// be blocked. So the part of the segment inside the first few of them does not count: the rest of
// each voxel does, which stops a ray that leaves its own surface's content to meet another surface
// in the same voxel. Without boxes a content is its whole voxel.
bool leaveStartContents(inout GridSegment segment) {
  // The segment starts inside the grid (enter is 0); most rays start outside every content and pay
  // for one test only.
  for (int i = 0; i <= kStartContentsLeft; ++i) {
    ivec3 voxel = ivec3(floor(segment.start + segment.direction * segment.enter));
    if (!voxelOccupied(voxel)) return true;
    vec2 inside = contentInterval(segment.start, segment.direction, segment.inverse,
                                  segment.enter, segment.leave, voxelContent(voxel),
                                  kVoxelBoxMargin);
    if (inside.x > segment.enter || inside.x > inside.y) return true;
    if (i == kStartContentsLeft || inside.y >= segment.leave) return false;
    // Past the content by a thousandth of a voxel along the segment's main axis, more than the
    // walks' rounding, so that the traversal does not meet it again.
    vec3 magnitude = abs(segment.direction);
    segment.enter = inside.y + 1e-3 / max(max(magnitude.x, magnitude.y), magnitude.z);
  }
  return false;
}

// Exact traversal of every voxel the segment passes through (world grid only), but for the
// voxel contents it starts in (leaveStartContents); through the occupancy pyramid's cells when the
// grid has one and `skipEmptyCells` (the renderer's traversal; the column walk alone gives the
// same answers).
bool segmentBlockedDda(vec3 from, vec3 to, bool skipEmptyCells) {
  GridSegment segment;
  if (!clipToGrid(from, to, segment)) return false;
  // A segment that enters the grid from outside does not start at a surface.
  if (segment.enter == 0.0 && !leaveStartContents(segment)) return true;
  // Tested as one condition, which is constant in the default grid's programs, so that they hold
  // the columns' walk once, inside the cells' walk.
  if (!skipEmptyCells || !emptySpaceSkipping())
    return columnsBlocked(segment, segment.enter, segment.leave);
  return cellsBlocked(segment, skippingLevel());
}

bool segmentBlocked(vec3 from, vec3 to) {
  return exactTraversal() ? segmentBlockedDda(from, to, true) : segmentBlockedUniform(from, to);
}

// The thickness of the layer of voxels that a plane with unit normal `normal` marks: its voxels
// reach dot(|normal|, voxel size) from it. A screen grid's voxels vary in size; it uses the
// diagonal of a voxel at mid depth.
float voxelLayer(vec3 normal) {
  return worldGrid() ? dot(abs(normal), grid.voxelSize.xyz) : grid.voxelSize.w;
}

// Part of a voxel by which a ray starts off a plane's box along the plane's main axis: a slice
// (1/32) and a margin.
const float kBoxedLayer = 0.05;
// Part of the layer of voxels by which a ray starts off a slanted face: its slabs hold it to about
// a slice of a sixteenth of the voxel's extent along their normals, but on a curved surface (the
// resting bunny) they hold the curve inside the voxel. Measured on five shadow scenes with 0.1 to
// 1 (docs/shadows.md): 0.1 left dark blotches on the bunny, where its rays met its own surface in
// the next voxel, and 0.35 or more let the bunny's chest see the light through its head.
const float kSlantedLayer = 0.25;

// How far a shadow ray's start moves off a surface with unit normal `normal`: the origin offset
// times the thickness of what the surface marks around it, so that the ray starts outside it and,
// moving away from the plane, never meets it again. In general the layer of voxels (voxelLayer).
// With boxes (voxelContent), a face parallel to two axes (to within a twentieth, about 3 degrees)
// marks only its slice and a margin, and starts a sixteenth of a voxel off, where the whole layer
// kept contact shadows a voxel and a quarter short; a slanted face a quarter of the layer
// (kSlantedLayer).
float surfaceOffset(vec3 normal) {
  float layer = voxelLayer(normal);
  if (worldGrid() && boxesInVoxels()) {
    vec3 extent = abs(normal) * grid.voxelSize.xyz;
    float along = max(max(extent.x, extent.y), extent.z);
    layer = layer - along <= kBoxedLayer * along ? layer - along + kBoxedLayer * along
                                                 : kSlantedLayer * layer;
  }
  return grid.boundsMin.w * layer;
}

// Where a shadow ray starts: off its surface (unit normal `normal`) by surfaceOffset.
vec3 offSurface(vec3 position, vec3 normal) {
  return position + normal * surfaceOffset(normal);
}

// The fraction of the way from a light's point back towards `from` at which a shadow ray to that
// point stops: where it comes within the origin offset times the layer of voxels (voxelLayer) of
// the light's plane, so that neither the light's quad nor a ceiling it is set in shadows it. The
// ray keeps its direction (moving its end along the light's normal instead turned every ray
// towards a point off the light and moved the shadows' edges: the slab above the view measured
// 5.5e-4 against reference-vpl where it measures 4.7e-5 now). 1: `from` lies within that
// distance of the plane, or behind it.
float lightEndFraction(vec3 from, vec3 pointOnLight, vec3 lightNormal) {
  float height = dot(from - pointOnLight, lightNormal);
  return height > 0.0 ? grid.boundsMin.w * voxelLayer(lightNormal) / height : 1.0;
}

// Whether a VPL (at vplPosition, emitting along vplNormal) is visible from a surface point. The
// ray starts off the point's surface (offSurface) and stops short of the light
// (lightEndFraction); a point that close to the light's plane sees it.
bool vplVisible(vec3 position, vec3 normal, vec3 vplPosition, vec3 vplNormal) {
  vec3 from = offSurface(position, normal);
  float fraction = lightEndFraction(from, vplPosition, vplNormal);
  if (fraction >= 1.0) return true;
  return !segmentBlocked(from, mix(vplPosition, from, fraction));
}

// The clear-light test: whether no shadow ray from a surface point to any VPL of a quad light
// can meet an occupied voxel, so that every one of its VPLs is visible without tracing a ray
// (world grid; the traversal visits only voxels its segment passes through). The rays run from
// the point's offSurface end towards the VPLs and stop the same fraction short of each
// (lightEndFraction: the light's plane is the same for all), so they fill the pyramid of the
// point's end and the light's corners moved that fraction towards it (light_pyramid.glsl). When
// no occupied voxel meets that pyramid, no ray can be blocked.
//
// The test descends the occupancy pyramid from its coarsest level and visits only occupied cells
// whose box of occupied voxels may meet the pyramid, and at the last level the voxels whose box
// of surfaces (voxelContent) may meet it. Each box is grown by kOccupiedBoxMargin voxels, more than
// the traversal's rounding and its kVoxelBoxMargin, so that the test never calls clear a ray that
// the traversal finds blocked. After kClearLightVisits cells (llvmpipe ends an invocation's loops
// after 65535 iterations, and each visit takes 9) it gives up and answers false: the VPLs are
// then traced.
const int kClearLightVisits = 4096;

// Whether the pyramid may meet the occupied voxels of a cell of the occupancy pyramid: none when
// the cell is empty, or when a test separates the pyramid from their box.
bool pyramidMeetsCell(LightPyramid pyramid, int level, ivec3 cell) {
  ivec3 occupiedLow;
  ivec3 occupiedHigh;
  if (!cellBounds(level, cell, occupiedLow, occupiedHigh)) return false;
  vec3 low = vec3(occupiedLow);
  vec3 high = vec3(occupiedHigh);
  if (level == 0) {
    VoxelContent content = voxelContent(cell);
    low = content.low;
    high = content.high;
  }
  return pyramidMeetsBox(pyramid, low - kOccupiedBoxMargin, high + kOccupiedBoxMargin);
}

bool lightClearFrom(vec3 position, vec3 normal, vec3 lightCorners[4], vec3 lightNormal) {
  int top = grid.occupancy.x;
  if (top == 0) return false;
  vec3 start = offSurface(position, normal);
  float fraction = lightEndFraction(start, lightCorners[0], lightNormal);
  // So close to the light's plane, every ray sees the light without a test (vplVisible).
  if (fraction >= 1.0) return false;
  vec3 corners[5];
  corners[0] = gridCoordinates(start);
  for (int i = 0; i < 4; ++i)
    corners[i + 1] = gridCoordinates(mix(lightCorners[i], start, fraction));
  LightPyramid pyramid = lightPyramid(corners);

  // Depth-first; each visit replaces a cell by at most 8 children, so the stack holds at most
  // 1 + 7 * top cells.
  ivec4 stack[8 * kMaxOccupancyLevels];
  ivec3 topCells = grid.occupancyLevels[top - 1].xyz;
  float topSize = float(1 << top);
  ivec3 first = clamp(ivec3(floor(pyramid.low / topSize)), ivec3(0), topCells - 1);
  ivec3 last = clamp(ivec3(floor(pyramid.high / topSize)), ivec3(0), topCells - 1);
  int visits = 0;
  // The coarsest level has at most 4 cells per axis (voxelize.cpp). A loop over the cells of the
  // pyramid's box only: llvmpipe pays for every iteration, even one that does nothing.
  ivec3 span = last - first + 1;
  for (int i = 0; i < span.x * span.y * span.z; ++i) {
    ivec3 cell = first + ivec3(i % span.x, (i / span.x) % span.y, i / (span.x * span.y));
    if (!pyramidMeetsCell(pyramid, top, cell)) continue;
    stack[0] = ivec4(cell, top);
    int depth = 1;
    while (depth > 0) {
      if (++visits > kClearLightVisits) return false;
      ivec4 parent = stack[--depth];
      int level = parent.w - 1;
      for (int child = 0; child < 8; ++child) {
        ivec3 childCell = 2 * parent.xyz + ivec3(child & 1, (child >> 1) & 1, child >> 2);
        if (!pyramidMeetsCell(pyramid, level, childCell)) continue;
        if (level == 0) return false;
        stack[depth++] = ivec4(childCell, level);
      }
    }
  }
  return true;
}
