// Exact shadow rays through the two-level bounding volume hierarchy (shared.h describes the
// layout, src/render/bvh_gpu.cpp builds it). Declares its buffers itself; include after shared.h
// and light_pyramid.glsl. Any-hit: a shadow ray stops at the first triangle it meets. Every
// triangle blocks from both sides, the quad lights' too, as in the reference.

layout(std430, binding = kBvhHeaderBinding) readonly buffer BvhHeaderBlock { BvhHeader bvh; };
layout(std430, binding = kBvhTopNodeBinding) readonly buffer BvhTopNodes { BvhNode topNodes[]; };
layout(std430, binding = kBvhInstanceBinding) readonly buffer BvhInstances {
  BvhInstance instances[];
};
layout(std430, binding = kBvhNodeBinding) readonly buffer BvhNodes { BvhCompactNode nodes[]; };
layout(std430, binding = kBvhTriangleBinding) readonly buffer BvhTriangles {
  BvhTriangle triangles[];
};

// Where the ray origin + t * direction, t in [0, tFar], enters the box, or -1 when it misses
// it; `inverse` is 1 / direction (huge along an axis it does not move on).
float rayEntersBox(vec3 origin, vec3 inverse, float tFar, vec3 boxMin, vec3 boxMax) {
  vec3 toMin = (boxMin - origin) * inverse;
  vec3 toMax = (boxMax - origin) * inverse;
  vec3 near = min(toMin, toMax);
  vec3 far = max(toMin, toMax);
  float enter = max(max(near.x, near.y), max(near.z, 0.0));
  float leave = min(min(far.x, far.y), min(far.z, tFar));
  return enter <= leave ? enter : -1.0;
}

// Moller-Trumbore, both sides: whether the ray meets the triangle at some t in (0, tFar).
bool rayMeetsTriangle(vec3 origin, vec3 direction, float tFar, BvhTriangle triangle) {
  vec3 edge1 = triangle.edge1.xyz;
  vec3 edge2 = triangle.edge2.xyz;
  vec3 p = cross(direction, edge2);
  float determinant = dot(edge1, p);
  if (determinant == 0.0) return false;  // parallel to the triangle's plane
  float inverse = 1.0 / determinant;
  vec3 fromCorner = origin - triangle.corner.xyz;
  float u = dot(fromCorner, p) * inverse;
  if (u < 0.0 || u > 1.0) return false;
  vec3 q = cross(fromCorner, edge1);
  float v = dot(direction, q) * inverse;
  if (v < 0.0 || u + v > 1.0) return false;
  float t = dot(edge2, q) * inverse;
  return t > 0.0 && t < tFar;
}

// Avoids the 0 * inf = NaN of an axis the ray does not move along.
vec3 safeInverse(vec3 direction) {
  return 1.0 / (direction + vec3(equal(direction, vec3(0.0))) * 1e-30);
}

// What a node points to: its first child or triangle, and its triangle count (0: inner node).
ivec2 nodeContents(BvhNode node) {
  return ivec2(floatBitsToInt(node.boundsMin.w), floatBitsToInt(node.boundsMax.w));
}
ivec2 nodeContents(BvhCompactNode node) {
  return ivec2(node.words.w >> kBvhCompactCountBits,
               node.words.w & ((1u << kBvhCompactCountBits) - 1u));
}

// A compact node's box, in steps of its object's node grid.
vec3 gridBoxLow(BvhCompactNode node) {
  return vec3(node.words.x & 0xffffu, node.words.x >> 16, node.words.y & 0xffffu);
}
vec3 gridBoxHigh(BvhCompactNode node) {
  return vec3(node.words.y >> 16, node.words.z & 0xffffu, node.words.z >> 16);
}

// Any hit in one bottom level, the ray already in its object's coordinates (t is the same
// parameter as in the world: the transform is affine). The boxes are tested in the steps of the
// level's node grid (`nodeGrid`, shared.h), where the ray's t stays the same too; the triangles
// in the object's coordinates. Each step tests both children of an inner node and goes on into
// the one the ray enters first (the likelier to block), keeping the other for later. The walk and
// its stack hold a node's contents, read with its box when its parent's step tested it, so that
// no node is read twice: reading it again on each step made the dragon's level 0 14 to 33% slower
// on llvmpipe (docs/shadows.md).
bool bottomLevelBlocked(int root, vec4 nodeGrid, vec3 origin, vec3 direction, float tFar) {
  vec3 gridOrigin = (origin - nodeGrid.xyz) / nodeGrid.w;
  vec3 inverse = safeInverse(direction / nodeGrid.w);
  BvhCompactNode rootNode = nodes[root];
  if (rayEntersBox(gridOrigin, inverse, tFar, gridBoxLow(rootNode), gridBoxHigh(rootNode)) < 0.0)
    return false;
  ivec2 stack[kBvhStackSize];
  int depth = 0;
  ivec2 node = nodeContents(rootNode);
  while (true) {
    int first = node.x;
    int count = node.y;
    if (count > 0) {
      for (int i = first; i < first + count; ++i)
        if (rayMeetsTriangle(origin, direction, tFar, triangles[i])) return true;
      if (depth == 0) return false;
      node = stack[--depth];
      continue;
    }
    BvhCompactNode left = nodes[first];
    BvhCompactNode right = nodes[first + 1];
    float enterLeft = rayEntersBox(gridOrigin, inverse, tFar, gridBoxLow(left), gridBoxHigh(left));
    float enterRight =
        rayEntersBox(gridOrigin, inverse, tFar, gridBoxLow(right), gridBoxHigh(right));
    ivec2 leftNode = nodeContents(left);
    ivec2 rightNode = nodeContents(right);
    if (enterLeft >= 0.0 && enterRight >= 0.0) {
      bool leftFirst = enterLeft <= enterRight;
      stack[depth++] = leftFirst ? rightNode : leftNode;
      node = leftFirst ? leftNode : rightNode;
    } else if (enterLeft >= 0.0) {
      node = leftNode;
    } else if (enterRight >= 0.0) {
      node = rightNode;
    } else {
      if (depth == 0) return false;
      node = stack[--depth];
    }
  }
  return false;
}

// Whether a triangle of the scene meets the segment origin + t * direction, t in (0, tFar).
bool bvhSegmentBlocked(vec3 origin, vec3 direction, float tFar) {
  if (bvh.counts.y == 0) return false;
  vec3 inverse = safeInverse(direction);
  int stack[kBvhStackSize];
  int depth = 0;
  int node = 0;
  while (true) {
    BvhNode current = topNodes[node];
    ivec2 contents = nodeContents(current);
    int first = contents.x;
    int count = contents.y;
    if (rayEntersBox(origin, inverse, tFar, current.boundsMin.xyz, current.boundsMax.xyz) >= 0.0) {
      if (count == 0) {
        stack[depth++] = first + 1;
        node = first;
        continue;
      }
      for (int i = first; i < first + count; ++i) {
        BvhInstance instance = instances[i];
        vec3 objectOrigin = vec3(dot(instance.objectFromWorld[0], vec4(origin, 1.0)),
                                 dot(instance.objectFromWorld[1], vec4(origin, 1.0)),
                                 dot(instance.objectFromWorld[2], vec4(origin, 1.0)));
        vec3 objectDirection = vec3(dot(instance.objectFromWorld[0].xyz, direction),
                                    dot(instance.objectFromWorld[1].xyz, direction),
                                    dot(instance.objectFromWorld[2].xyz, direction));
        if (bottomLevelBlocked(instance.root.x, instance.nodeGrid, objectOrigin, objectDirection,
                               tFar))
          return true;
      }
    }
    if (depth == 0) return false;
    node = stack[--depth];
  }
  return false;
}

// The clear-light test through the hierarchy: whether no triangle meets the pyramid of the shadow
// rays from its apex (corners[0]) to the points of its base quad (corners[1] to [4];
// light_pyramid.glsl), so that every ray from the apex to a VPL in the quad is clear. Nodes are
// visited where their boxes may meet the pyramid; a triangle is left out when its bounding box, a
// face of the pyramid, or its own plane (all five corners on one side) separates them. Boxes grow,
// and planes separate only, by more than kPyramidRoundingMargin of the largest coordinate: at least
// 8 units in the last place of a float there (2^-23 relative), where the ray tests' rounding is a
// few, so that the test never calls clear a ray the traversal finds blocked. Not more: the rays
// stop 1e-4 of their length short of their VPL, so the pyramid's base lies that close to the
// light's own quad, and a texel a few centimetres from the light's plane would never pass (4e-6
// failed 83 texels of the demo's coarsest level that way). After kBvhClearLightVisits nodes it
// gives up and answers false (llvmpipe ends an invocation's loops after 65535 iterations, and a
// leaf's visit takes up to 9: bvh_build.h's kBvhLeafSize + 1).
const float kPyramidRoundingMargin = 1e-6;
const int kBvhClearLightVisits = 2048;

struct PyramidInSpace {
  LightPyramid pyramid;
  vec3 corners[5];
  float margin;
};

PyramidInSpace pyramidInSpace(vec3 corners[5]) {
  PyramidInSpace space;
  space.corners = corners;
  space.pyramid = lightPyramid(corners);
  vec3 reach = max(abs(space.pyramid.low), abs(space.pyramid.high));
  space.margin = kPyramidRoundingMargin * max(max(reach.x, reach.y), reach.z);
  return space;
}

bool pyramidMeetsNode(PyramidInSpace space, BvhNode node) {
  return pyramidMeetsBox(space.pyramid, node.boundsMin.xyz - space.margin,
                         node.boundsMax.xyz + space.margin);
}

// A compact node's box in its object's coordinates: its steps are whole numbers, exact in a float,
// and the step of growth on each side is far more than the rounding here.
bool pyramidMeetsNode(PyramidInSpace space, BvhCompactNode node, vec4 nodeGrid) {
  return pyramidMeetsBox(space.pyramid, nodeGrid.xyz + gridBoxLow(node) * nodeGrid.w - space.margin,
                         nodeGrid.xyz + gridBoxHigh(node) * nodeGrid.w + space.margin);
}

bool pyramidMeetsTriangle(PyramidInSpace space, BvhTriangle triangle) {
  vec3 a = triangle.corner.xyz;
  vec3 b = a + triangle.edge1.xyz;
  vec3 c = a + triangle.edge2.xyz;
  if (!pyramidMeetsBox(space.pyramid, min(a, min(b, c)) - space.margin,
                       max(a, max(b, c)) + space.margin))
    return false;
  vec3 normal = cross(triangle.edge1.xyz, triangle.edge2.xyz);
  float margin = space.margin * length(normal);
  if (margin == 0.0) return true;  // degenerate: no plane to separate by
  // Written out rather than looped over: each iteration counts towards llvmpipe's limit.
  float apex = dot(normal, space.corners[0] - a);
  vec4 base = vec4(dot(normal, space.corners[1] - a), dot(normal, space.corners[2] - a),
                   dot(normal, space.corners[3] - a), dot(normal, space.corners[4] - a));
  float nearest = min(apex, min(min(base.x, base.y), min(base.z, base.w)));
  float farthest = max(apex, max(max(base.x, base.y), max(base.z, base.w)));
  return nearest <= margin && farthest >= -margin;
}

// Whether a triangle of one bottom level may meet the pyramid (in its object's coordinates);
// `visits` counts the nodes visited, across the bottom levels of one test.
bool bottomLevelMeetsPyramid(int root, vec4 nodeGrid, PyramidInSpace space, inout int visits) {
  int stack[kBvhStackSize];
  int depth = 0;
  if (pyramidMeetsNode(space, nodes[root], nodeGrid)) stack[depth++] = root;
  while (depth > 0) {
    if (++visits > kBvhClearLightVisits) return true;
    ivec2 contents = nodeContents(nodes[stack[--depth]]);
    int first = contents.x;
    int count = contents.y;
    if (count > 0) {
      for (int i = first; i < first + count; ++i)
        if (pyramidMeetsTriangle(space, triangles[i])) return true;
      continue;
    }
    if (pyramidMeetsNode(space, nodes[first], nodeGrid)) stack[depth++] = first;
    if (pyramidMeetsNode(space, nodes[first + 1], nodeGrid)) stack[depth++] = first + 1;
  }
  return false;
}

bool bvhPyramidClear(vec3 worldCorners[5]) {
  if (bvh.counts.y == 0) return true;
  PyramidInSpace world = pyramidInSpace(worldCorners);
  int visits = 0;
  int stack[kBvhStackSize];
  int depth = 0;
  if (pyramidMeetsNode(world, topNodes[0])) stack[depth++] = 0;
  while (depth > 0) {
    if (++visits > kBvhClearLightVisits) return false;
    BvhNode current = topNodes[stack[--depth]];
    ivec2 contents = nodeContents(current);
    int first = contents.x;
    int count = contents.y;
    if (count == 0) {
      if (pyramidMeetsNode(world, topNodes[first])) stack[depth++] = first;
      if (pyramidMeetsNode(world, topNodes[first + 1])) stack[depth++] = first + 1;
      continue;
    }
    for (int i = first; i < first + count; ++i) {
      BvhInstance instance = instances[i];
      vec3 objectCorners[5];
      for (int c = 0; c < 5; ++c)
        objectCorners[c] = vec3(dot(instance.objectFromWorld[0], vec4(worldCorners[c], 1.0)),
                                dot(instance.objectFromWorld[1], vec4(worldCorners[c], 1.0)),
                                dot(instance.objectFromWorld[2], vec4(worldCorners[c], 1.0)));
      if (bottomLevelMeetsPyramid(instance.root.x, instance.nodeGrid, pyramidInSpace(objectCorners),
                                  visits))
        return false;
    }
  }
  return true;
}

// Whether every VPL of a quad light is visible from a point `origin` on a surface whose plane
// has the unit normal `offNormal`, with the ends of vplVisibleFrom's rays: the rays start off the
// surface and stop short of the light, so their pyramid's base is the quad moved towards the
// start by that fraction.
bool bvhLightClearFrom(vec3 origin, vec3 offNormal, vec3 lightCorners[4]) {
  vec3 corners[5];
  corners[0] = origin + offNormal * bvh.rayOffsets.x;
  for (int i = 0; i < 4; ++i)
    corners[i + 1] = corners[0] + (1.0 - bvh.rayOffsets.y) * (lightCorners[i] - corners[0]);
  return bvhPyramidClear(corners);
}

// Whether a VPL (at vplPosition) is visible from a point `origin` on a surface whose plane has
// the unit normal `offNormal`, as the reference decides it: the ray starts a small distance off
// the surface along it (scaled to the scene) and stops just short of the VPL, so the light's own
// surface does not block it.
bool vplVisibleFrom(vec3 origin, vec3 offNormal, vec3 vplPosition) {
  vec3 from = origin + offNormal * bvh.rayOffsets.x;
  vec3 towardsVpl = vplPosition - from;
  return !bvhSegmentBlocked(from, towardsVpl, 1.0 - bvh.rayOffsets.y);
}

bool vplVisible(vec3 position, vec3 normal, vec3 vplPosition, vec3 vplNormal) {
  return vplVisibleFrom(position, normal, vplPosition);
}
