#version 450 core
#extension GL_GOOGLE_include_directive : require
// World-grid voxelization in three dispatches per pass. The first runs one thread per triangle.
// In the passes over surfaces it marks a triangle that lies inside one voxel (most of a fine
// mesh's) at once and lists the others, so that their longer work does not hold up the threads
// beside them (llvmpipe runs neighbouring threads in SIMD lanes, which wait for the slowest). The
// second, an indirect dispatch, runs one thread per listed triangle over the first tile of voxel
// columns its bounding box covers, which is all of a small triangle, and lists the triangles that
// cover more (in the solid pass the first dispatch does this for every triangle); the third runs
// one thread per triangle so listed and further tile.
// Surface pass (kVoxelizeSurface): sets every voxel the triangle overlaps (a conservative
// triangle/box test: the triangle's plane crosses the box, and the box overlaps the triangle in
// each of the three axis projections), so thin geometry is never missed.
// Plane-normal and box passes (kVoxelizePlaneNormals, then kVoxelizeBoxes; after the surface pass,
// the occupancy pyramid and voxel_bricks.comp): the same voxels. The first picks each voxel's two
// plane normals among its triangles' normals; the second marks in the voxel's brick the box of
// what of each triangle lies inside the voxel and the slabs along those normals that hold it
// (GpuVoxelGrid::occupancy), so that the traversal can test the surfaces' content instead of the
// whole voxel.
// Solid pass (kVoxelizeSolid): for every voxel column whose centre line crosses the triangle,
// flips all voxels from the crossing to the end of the column (XOR). Inside a closed mesh an odd
// number of crossings remain, so it fills solid; the surface pass then runs as well.
#include "shared.h"

layout(local_size_x = 64) in;

layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) buffer Voxels { uint voxels[]; };
layout(std430, binding = kGeometryVertexBinding) readonly buffer Vertices { float vertexData[]; };
layout(std430, binding = kGeometryIndexBinding) readonly buffer Indices { uint indices[]; };

#include "voxel_content.glsl"

layout(std430, binding = kTriangleListBinding) buffer TriangleLists {
  // Per list (kSpanningTriangleList, kLargeTriangleList): groupsX counts the listed triangles'
  // work groups, texelCount the listed triangles; the large list's groupsY is set to the further
  // tiles per triangle before the first dispatch.
  DispatchIndirect listDispatch[2];
  // The lists interleaved: list k's entry i at 2 i + k.
  uint listedTriangles[];
};

// This dispatch's triangles: a batch of at most as many work groups as a dispatch may have
// (voxelize.cpp), so that the second dispatch's groups stay within that limit too.
uniform uint firstTriangle;
uniform uint endTriangle;
// The pass (kVoxelizeSolid, kVoxelizeSurface, kVoxelizePlaneNormals or kVoxelizeBoxes) and the
// dispatch (kVoxelizeEveryTriangle, kVoxelizeSpanningTriangles or kVoxelizeFurtherTiles) are
// constants, a program for each (voxelize.cpp): llvmpipe runs the code of a branch that all its
// threads skip as well (with its SIMD lanes masked), so a branch on a uniform would cost the
// surface pass the box pass's code. The defaults let glslangValidator check the file alone.
#ifndef VOXELIZE_PASS
#define VOXELIZE_PASS kVoxelizeBoxes
#endif
#ifndef VOXELIZE_DISPATCH
#define VOXELIZE_DISPATCH kVoxelizeEveryTriangle
#endif
const int pass = VOXELIZE_PASS;
const int dispatchStage = VOXELIZE_DISPATCH;
// Each invocation handles one triangle in one tile of kTileSize^2 voxel columns (along z for
// solid fill, along the triangle's main normal axis for surfaces), counted from the first
// column of the triangle's bounding box: llvmpipe ends an invocation's loops after 65535
// iterations in all, fewer than a large triangle's voxels.
const int kTileSize = 16;
uniform int tilesPerSide;

vec3 vertexPosition(uint index) {
  uint base = index * uint(kFloatsPerVertex);
  return vec3(vertexData[base], vertexData[base + 1u], vertexData[base + 2u]);
}

uint wordIndex(ivec3 voxel) {
  return uint((voxel.y * grid.resolution.x + voxel.x) * grid.resolution.w + voxel.z / 32);
}

// Edge functions of one axis projection (a, b the two axes), offset to the box corner that
// makes the test conservative.
struct ProjectedEdges {
  vec2 normals[3];
  float offsets[3];
};

ProjectedEdges projectedEdges(vec3 v[3], int a, int b, float orientation, vec2 boxSize) {
  ProjectedEdges edges;
  for (int i = 0; i < 3; ++i) {
    vec3 edge = v[(i + 1) % 3] - v[i];
    vec2 normal = vec2(-edge[b], edge[a]) * orientation;
    edges.normals[i] = normal;
    edges.offsets[i] = -dot(normal, vec2(v[i][a], v[i][b])) +
                       max(0.0, boxSize.x * normal.x) + max(0.0, boxSize.y * normal.y);
  }
  return edges;
}

bool insideProjection(ProjectedEdges edges, vec2 corner) {
  for (int i = 0; i < 3; ++i) {
    if (dot(edges.normals[i], corner) + edges.offsets[i] < 0.0) return false;
  }
  return true;
}

// Grid coordinates of a world point: voxel v spans [v, v + 1) on each axis.
vec3 gridPoint(vec3 world) {
  return (world - grid.boundsMin.xyz) / grid.voxelSize.xyz;
}

// The plane-normal pass: offers the triangle's normal (grid coordinates) as one of the voxel's
// two plane normals: of all the triangles in a voxel, the first plane gets the largest code and
// the second the smallest (stored as 0xffff minus it, so that both are an atomicMax), which any
// order of the threads gives alike. Two faces meeting at an edge get one each.
void offerPlaneNormal(ivec3 voxel, vec3 v[3]) {
  uint first = voxelContentFirstWord(voxel);
  if (first == kNoBrick) return;
  vec3 normal =
      normalize(cross(gridPoint(v[1]) - gridPoint(v[0]), gridPoint(v[2]) - gridPoint(v[0])));
  uint code = encodePlaneNormal(normal);
  atomicMax(voxels[first + 3u], code << 16);
  atomicMax(voxels[first + 4u], (0xffffu - code) << 16);
}

// The bounds of the part of a triangle inside a voxel: its box, and its heights along the voxel's
// two plane normals (from the voxel's centre).
struct ClippedBounds {
  vec3 low;
  vec3 high;
  vec2 heightLow;
  vec2 heightHigh;
};

void includePoint(inout ClippedBounds bounds, vec3 point, vec3 normals[2], vec3 centre) {
  bounds.low = min(bounds.low, point);
  bounds.high = max(bounds.high, point);
  vec2 heights = vec2(dot(normals[0], point - centre), dot(normals[1], point - centre));
  bounds.heightLow = min(bounds.heightLow, heights);
  bounds.heightHigh = max(bounds.heightHigh, heights);
}

// Grows the voxel by which the box pass bounds a triangle, in voxels: the surface pass's
// conservative test passes a triangle that only touches the voxel, which an exact test may find
// outside it by rounding.
const float kClipMargin = 1e-4;

// The bounds of the triangle `corners` (grid coordinates) inside the box low to high, without
// clipping it (llvmpipe compiles a clipped polygon's arrays into a voxelization ten times slower):
// the part is a polygon whose corners are the triangle's corners inside the box, the crossings of
// its edges with the box's faces, and the crossings of the box's edges with it; any bound of a
// linear function over the part is one of theirs. False when there is none (the triangle only
// touches the box).
bool clippedBounds(vec3 corners[3], vec3 low, vec3 high, vec3 normals[2], vec3 centre,
                   out ClippedBounds bounds) {
  bounds.low = vec3(1e30);
  bounds.high = vec3(-1e30);
  bounds.heightLow = vec2(1e30);
  bounds.heightHigh = vec2(-1e30);
  // Most triangles of a fine mesh lie inside one voxel: their corners are the part's. The first
  // dispatch hands this function only such triangles, so its program holds none of the rest,
  // which llvmpipe would run for every thread (the dragon's voxelization at 1024x1024: 484 and
  // 494 ms a frame against 553 and 557 ms with it).
  if (dispatchStage == kVoxelizeEveryTriangle ||
      (all(greaterThanEqual(min(min(corners[0], corners[1]), corners[2]), low)) &&
       all(lessThanEqual(max(max(corners[0], corners[1]), corners[2]), high)))) {
    for (int i = 0; i < 3; ++i) includePoint(bounds, corners[i], normals, centre);
    return true;
  }
  for (int i = 0; i < 3; ++i) {
    vec3 from = corners[i];
    vec3 to = corners[(i + 1) % 3];
    if (all(greaterThanEqual(from, low)) && all(lessThanEqual(from, high)))
      includePoint(bounds, from, normals, centre);
    for (int face = 0; face < 6; ++face) {
      int axis = face >> 1;
      float bound = (face & 1) == 0 ? low[axis] : high[axis];
      float along = to[axis] - from[axis];
      if (along == 0.0) continue;
      float t = (bound - from[axis]) / along;
      if (t < 0.0 || t > 1.0) continue;
      vec3 point = mix(from, to, t);
      point[axis] = bound;
      if (all(greaterThanEqual(point, low)) && all(lessThanEqual(point, high)))
        includePoint(bounds, point, normals, centre);
    }
  }
  // The box's twelve edges: along each axis, at each pair of the other two axes' bounds. A
  // crossing within a ten-thousandth of a voxel of the triangle counts, so that rounding cannot
  // leave out a corner of the part.
  vec3 normal = cross(corners[1] - corners[0], corners[2] - corners[0]);
  float plane = dot(normal, corners[0]);
  vec3 sides[3] = vec3[](corners[1] - corners[0], corners[2] - corners[1], corners[0] - corners[2]);
  vec3 tolerance = -kClipMargin * length(normal) *
                   vec3(length(sides[0]), length(sides[1]), length(sides[2]));
  for (int edge = 0; edge < 12; ++edge) {
    int axis = edge >> 2;
    int u = (axis + 1) % 3;
    int w = (axis + 2) % 3;
    if (normal[axis] == 0.0) continue;
    vec3 point;
    point[u] = (edge & 1) == 0 ? low[u] : high[u];
    point[w] = (edge & 2) == 0 ? low[w] : high[w];
    point[axis] = (plane - normal[u] * point[u] - normal[w] * point[w]) / normal[axis];
    if (point[axis] < low[axis] || point[axis] > high[axis]) continue;
    vec3 reach = vec3(dot(cross(sides[0], point - corners[0]), normal),
                      dot(cross(sides[1], point - corners[1]), normal),
                      dot(cross(sides[2], point - corners[2]), normal));
    if (all(greaterThanEqual(reach, tolerance))) includePoint(bounds, point, normals, centre);
  }
  return bounds.low.x <= bounds.high.x;
}

// The box pass: marks in the voxel's words what of the triangle lies inside it: the slices of its
// box, and the slices along each of the voxel's two plane normals (the plane-normal pass's) that
// it spans. The box is exact, and a slab exact for a face whose normal its plane is.
void markBoxSlices(ivec3 voxel, vec3 v[3]) {
  uint first = voxelContentFirstWord(voxel);
  // The pool was too small this frame: voxelize.cpp grows it and voxelizes again.
  if (first == kNoBrick) return;
  vec3 corners[3] = vec3[](gridPoint(v[0]), gridPoint(v[1]), gridPoint(v[2]));
  uvec2 words = uvec2(voxels[first + 3u], voxels[first + 4u]) >> 16;
  vec3 normals[2] = vec3[](decodePlaneNormal(words.x), decodePlaneNormal(0xffffu - words.y));
  vec3 centre = vec3(voxel) + 0.5;
  ClippedBounds bounds;
  if (!clippedBounds(corners, vec3(voxel) - kClipMargin, vec3(voxel) + 1.0 + kClipMargin, normals,
                     centre, bounds))
    return;
  float boxSlices = float(kVoxelBoxSlices);
  ivec3 from = clamp(ivec3(floor((bounds.low - vec3(voxel)) * boxSlices)), 0, kVoxelBoxSlices - 1);
  ivec3 to = clamp(ivec3(floor((bounds.high - vec3(voxel)) * boxSlices)), 0, kVoxelBoxSlices - 1);
  for (int k = 0; k < 3; ++k)
    atomicOr(voxels[first + uint(k)], (~0u << uint(from[k])) & (~0u >> uint(31 - to[k])));
  float planeSlices = float(kVoxelPlaneSlices);
  for (int plane = 0; plane < 2; ++plane) {
    float extent = dot(abs(normals[plane]), vec3(1.0));
    int fromSlice = clamp(int(floor((bounds.heightLow[plane] / extent + 0.5) * planeSlices)), 0,
                          kVoxelPlaneSlices - 1);
    int toSlice = clamp(int(floor((bounds.heightHigh[plane] / extent + 0.5) * planeSlices)), 0,
                        kVoxelPlaneSlices - 1);
    atomicOr(voxels[first + 3u + uint(plane)],
             (~0u << uint(fromSlice)) & (~0u >> uint(31 - toSlice)));
  }
}

// What the surface passes do in a voxel the triangle overlaps.
void markVoxel(ivec3 voxel, vec3 v[3]) {
  if (pass == kVoxelizeBoxes)
    markBoxSlices(voxel, v);
  else if (pass == kVoxelizePlaneNormals)
    offerPlaneNormal(voxel, v);
  else
    atomicOr(voxels[wordIndex(voxel)], 1u << uint(voxel.z % 32));
}

// The first and the last voxel of the triangle's bounding box, on each axis.
void boundingVoxels(vec3 v[3], out ivec3 first, out ivec3 last) {
  vec3 size = grid.voxelSize.xyz;
  first = max(ivec3(floor((min(min(v[0], v[1]), v[2]) - grid.boundsMin.xyz) / size)), ivec3(0));
  last = min(ivec3(floor((max(max(v[0], v[1]), v[2]) - grid.boundsMin.xyz) / size)),
             grid.resolution.xyz - 1);
}

// Returns whether the triangle's columns extend beyond the first tile.
bool markSurface(vec3 v[3], ivec2 tile) {
  vec3 size = grid.voxelSize.xyz;
  vec3 normal = cross(v[1] - v[0], v[2] - v[0]);
  vec3 critical = vec3(normal.x > 0.0 ? size.x : 0.0, normal.y > 0.0 ? size.y : 0.0,
                       normal.z > 0.0 ? size.z : 0.0);
  float planeNear = dot(normal, critical - v[0]);
  float planeFar = dot(normal, (size - critical) - v[0]);
  ProjectedEdges xy = projectedEdges(v, 0, 1, normal.z >= 0.0 ? 1.0 : -1.0, size.xy);
  ProjectedEdges yz = projectedEdges(v, 1, 2, normal.x >= 0.0 ? 1.0 : -1.0, size.yz);
  ProjectedEdges zx = projectedEdges(v, 2, 0, normal.y >= 0.0 ? 1.0 : -1.0, size.zx);

  ivec3 first;
  ivec3 last;
  boundingVoxels(v, first, last);
  // Walk the tile's columns along the normal's main axis; in each, only the voxels the plane
  // can reach inside the column (a few), so the work per invocation stays small.
  vec3 magnitude = abs(normal);
  int axis =
      magnitude.x >= max(magnitude.y, magnitude.z) ? 0 : (magnitude.y >= magnitude.z ? 1 : 2);
  int uAxis = (axis + 1) % 3;
  int vAxis = (axis + 2) % 3;
  ivec2 columnsFirst = ivec2(first[uAxis], first[vAxis]);
  ivec2 columnsLast = ivec2(last[uAxis], last[vAxis]);
  ivec2 tileFirst = columnsFirst + tile * kTileSize;
  ivec2 tileLast = min(columnsLast, tileFirst + kTileSize - 1);
  float planeOffset = dot(normal, v[0]);
  for (int b = tileFirst.y; b <= tileLast.y; ++b) {
    for (int a = tileFirst.x; a <= tileLast.x; ++a) {
      // Where the plane crosses the column's four edges along the main axis.
      float lowest = 1e30;
      float highest = -1e30;
      for (int edge = 0; edge < 4; ++edge) {
        float u = grid.boundsMin[uAxis] + float(a + (edge & 1)) * size[uAxis];
        float w = grid.boundsMin[vAxis] + float(b + (edge >> 1)) * size[vAxis];
        float along = (planeOffset - normal[uAxis] * u - normal[vAxis] * w) / normal[axis];
        lowest = min(lowest, along);
        highest = max(highest, along);
      }
      int from = max(int(floor((lowest - grid.boundsMin[axis]) / size[axis])) - 1, first[axis]);
      int to = min(int(floor((highest - grid.boundsMin[axis]) / size[axis])) + 1, last[axis]);
      for (int c = from; c <= to; ++c) {
        ivec3 voxel;
        voxel[axis] = c;
        voxel[uAxis] = a;
        voxel[vAxis] = b;
        vec3 corner = grid.boundsMin.xyz + vec3(voxel) * size;
        float plane = dot(normal, corner);
        if ((plane + planeNear) * (plane + planeFar) > 0.0) continue;
        if (!insideProjection(xy, corner.xy) || !insideProjection(yz, corner.yz) ||
            !insideProjection(zx, corner.zx))
          continue;
        markVoxel(voxel, v);
      }
    }
  }
  return any(greaterThanEqual(columnsLast - columnsFirst, ivec2(kTileSize)));
}

// Half-open inside test, so a column through an edge shared by two triangles crosses once.
bool coversColumn(vec2 a, vec2 b, vec2 c, vec2 point, out vec3 weights) {
  float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (area == 0.0) return false;
  float w0 = ((b.x - point.x) * (c.y - point.y) - (b.y - point.y) * (c.x - point.x)) / area;
  float w1 = ((c.x - point.x) * (a.y - point.y) - (c.y - point.y) * (a.x - point.x)) / area;
  float w2 = 1.0 - w0 - w1;
  weights = vec3(w0, w1, w2);
  return w0 >= 0.0 && w1 >= 0.0 && w2 > 0.0 && !(w0 == 0.0 && w1 == 0.0);
}

// Returns whether the triangle's columns extend beyond the first tile.
bool flipColumns(vec3 v[3], ivec2 tile) {
  vec3 size = grid.voxelSize.xyz;
  vec3 low = min(min(v[0], v[1]), v[2]);
  vec3 high = max(max(v[0], v[1]), v[2]);
  ivec2 columnsFirst = max(ivec2(floor((low.xy - grid.boundsMin.xy) / size.xy - 0.5)), ivec2(0));
  ivec2 columnsLast = min(ivec2(ceil((high.xy - grid.boundsMin.xy) / size.xy - 0.5)),
                          grid.resolution.xy - 1);
  ivec2 first = columnsFirst + tile * kTileSize;
  ivec2 last = min(columnsLast, first + kTileSize - 1);
  for (int y = first.y; y <= last.y; ++y) {
    for (int x = first.x; x <= last.x; ++x) {
      vec2 centre = grid.boundsMin.xy + (vec2(x, y) + 0.5) * size.xy;
      vec3 weights;
      if (!coversColumn(v[0].xy, v[1].xy, v[2].xy, centre, weights)) continue;
      float depth = dot(weights, vec3(v[0].z, v[1].z, v[2].z));
      int slice = clamp(int(floor((depth - grid.boundsMin.z) / size.z + 0.5)), 0,
                        grid.resolution.z);
      if (slice == grid.resolution.z) continue;
      // Voxels whose centre lies beyond the crossing flip.
      for (int word = slice / 32; word < grid.resolution.w; ++word) {
        uint mask = word == slice / 32 ? ~0u << uint(slice % 32) : ~0u;
        atomicXor(voxels[wordIndex(ivec3(x, y, word * 32))], mask);
      }
    }
  }
  return any(greaterThanEqual(columnsLast - columnsFirst, ivec2(kTileSize)));
}

void listTriangle(int list, uint triangle) {
  uint listed = atomicAdd(listDispatch[list].texelCount, 1u);
  listedTriangles[2u * listed + uint(list)] = triangle;
  // One more work group each time a group of the next dispatch starts.
  if (listed % uint(gl_WorkGroupSize.x) == 0u) atomicAdd(listDispatch[list].groupsX, 1u);
}

void main() {
  uint triangle;
  ivec2 tile = ivec2(0);
  if (dispatchStage == kVoxelizeEveryTriangle) {
    triangle = firstTriangle + gl_GlobalInvocationID.x;
    if (triangle >= endTriangle) return;
  } else {
    int list = dispatchStage == kVoxelizeSpanningTriangles ? kSpanningTriangleList
                                                           : kLargeTriangleList;
    uint listed = gl_GlobalInvocationID.x;
    if (dispatchStage == kVoxelizeFurtherTiles) {
      // Neighbouring invocations take neighbouring tiles of one triangle (tile 0 was done by the
      // dispatch before), so that llvmpipe's SIMD lanes run alike: with a triangle each, a lane
      // whose tile lies inside its triangle held up the lanes beside it.
      uint furtherTiles = uint(tilesPerSide * tilesPerSide - 1);
      uint index = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x +
                   gl_GlobalInvocationID.x;
      listed = index / furtherTiles;
      uint further = index % furtherTiles + 1u;
      tile = ivec2(further % uint(tilesPerSide), further / uint(tilesPerSide));
    }
    if (listed >= listDispatch[list].texelCount) return;
    triangle = listedTriangles[2u * listed + uint(list)];
  }
  vec3 v[3] = vec3[](vertexPosition(indices[3u * triangle]),
                     vertexPosition(indices[3u * triangle + 1u]),
                     vertexPosition(indices[3u * triangle + 2u]));
  // Zero-area triangles (real scans have them) cover nothing; their edge tests would pass
  // everywhere in their bounding box.
  if (dot(cross(v[1] - v[0], v[2] - v[0]), cross(v[1] - v[0], v[2] - v[0])) == 0.0) return;
  if (dispatchStage == kVoxelizeEveryTriangle && pass != kVoxelizeSolid) {
    // A triangle inside one voxel: the only voxel markSurface would test, and one it overlaps.
    ivec3 first;
    ivec3 last;
    boundingVoxels(v, first, last);
    if (first == last)
      markVoxel(first, v);
    else
      listTriangle(kSpanningTriangleList, triangle);
    return;
  }
  bool beyondFirstTile = pass == kVoxelizeSolid ? flipColumns(v, tile) : markSurface(v, tile);
  if (dispatchStage != kVoxelizeFurtherTiles && beyondFirstTile)
    listTriangle(kLargeTriangleList, triangle);
}
