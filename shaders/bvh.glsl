// Exact shadow rays through the two-level bounding volume hierarchy (shared.h describes the
// layout, src/render/bvh_gpu.cpp builds it). Declares its buffers itself; include after
// shared.h. Any-hit: a shadow ray stops at the first triangle it meets. Every triangle blocks
// from both sides, the quad lights' too, as in the reference.

layout(std430, binding = kBvhHeaderBinding) readonly buffer BvhHeaderBlock { BvhHeader bvh; };
layout(std430, binding = kBvhTopNodeBinding) readonly buffer BvhTopNodes { BvhNode topNodes[]; };
layout(std430, binding = kBvhInstanceBinding) readonly buffer BvhInstances {
  BvhInstance instances[];
};
layout(std430, binding = kBvhNodeBinding) readonly buffer BvhNodes { BvhNode nodes[]; };
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

int childFirst(BvhChild child) { return floatBitsToInt(child.boundsMin.w); }
int childCount(BvhChild child) { return floatBitsToInt(child.boundsMax.w); }
float rayEntersChild(vec3 origin, vec3 inverse, float tFar, BvhChild child) {
  return rayEntersBox(origin, inverse, tFar, child.boundsMin.xyz, child.boundsMax.xyz);
}

// What a traversal learns from one fetch of an inner node: where the ray enters each child
// (negative: it does not), and each child's first and count.
struct NodeVisit {
  vec2 enter;
  ivec2 first;
  ivec2 count;
};
NodeVisit visitNode(BvhNode node, vec3 origin, vec3 inverse, float tFar) {
  return NodeVisit(vec2(rayEntersChild(origin, inverse, tFar, node.left),
                        rayEntersChild(origin, inverse, tFar, node.right)),
                   ivec2(childFirst(node.left), childFirst(node.right)),
                   ivec2(childCount(node.left), childCount(node.right)));
}

// The nodes a traversal keeps to visit later: the top level's, and above them those of the
// bottom level it is in (each level holds at most one per tree level).
int bvhStack[2 * kBvhStackSize];
int bvhStackDepth = 0;

// Where a traversal goes after an inner node whose leaves it has tested (visit.enter negative
// for them): into the inner child the ray enters first (the likelier to block), keeping the other
// for later; with neither, to the last node kept above `stackBase`; -1 when there is none.
int nextNode(NodeVisit visit, int stackBase) {
  vec2 enter = visit.enter;
  if (enter.x >= 0.0 && enter.y >= 0.0) {
    bool leftFirst = enter.x <= enter.y;
    bvhStack[bvhStackDepth++] = leftFirst ? visit.first.y : visit.first.x;
    return leftFirst ? visit.first.x : visit.first.y;
  }
  if (enter.x >= 0.0) return visit.first.x;
  if (enter.y >= 0.0) return visit.first.y;
  return bvhStackDepth > stackBase ? bvhStack[--bvhStackDepth] : -1;
}

bool leafBlocked(int first, int count, vec3 origin, vec3 direction, float tFar) {
  for (int i = first; i < first + count; ++i)
    if (rayMeetsTriangle(origin, direction, tFar, triangles[i])) return true;
  return false;
}

// Any hit in one bottom level (its root's first and count), the ray already in its object's
// coordinates (t is the same parameter as in the world: the transform is affine). A leaf the
// ray enters is tested at once, since it is what can end the ray.
bool bottomLevelBlocked(ivec2 root, vec3 origin, vec3 direction, float tFar) {
  if (root.y > 0) return leafBlocked(root.x, root.y, origin, direction, tFar);
  vec3 inverse = safeInverse(direction);
  int stackBase = bvhStackDepth;
  for (int node = root.x; node >= 0;) {
    NodeVisit visit = visitNode(nodes[node], origin, inverse, tFar);
    for (int side = 0; side < 2; ++side) {
      if (visit.enter[side] < 0.0 || visit.count[side] == 0) continue;
      if (leafBlocked(visit.first[side], visit.count[side], origin, direction, tFar)) return true;
      visit.enter[side] = -1.0;
    }
    node = nextNode(visit, stackBase);
  }
  return false;
}

// Any hit in the instances first to first + count - 1 of the top level.
bool instancesBlocked(int first, int count, vec3 origin, vec3 direction, float tFar) {
  for (int i = first; i < first + count; ++i) {
    BvhInstance instance = instances[i];
    vec3 objectOrigin = vec3(dot(instance.objectFromWorld[0], vec4(origin, 1.0)),
                             dot(instance.objectFromWorld[1], vec4(origin, 1.0)),
                             dot(instance.objectFromWorld[2], vec4(origin, 1.0)));
    vec3 objectDirection = vec3(dot(instance.objectFromWorld[0].xyz, direction),
                                dot(instance.objectFromWorld[1].xyz, direction),
                                dot(instance.objectFromWorld[2].xyz, direction));
    if (bottomLevelBlocked(instance.root.xy, objectOrigin, objectDirection, tFar)) return true;
  }
  return false;
}

// Whether a triangle of the scene meets the segment origin + t * direction, t in (0, tFar).
// The top level is walked as a bottom level is, with instances in its leaves.
bool bvhSegmentBlocked(vec3 origin, vec3 direction, float tFar) {
  if (bvh.counts.x == 0) return false;
  bvhStackDepth = 0;
  vec3 inverse = safeInverse(direction);
  if (rayEntersChild(origin, inverse, tFar, bvh.topRoot) < 0.0) return false;
  int rootCount = childCount(bvh.topRoot);
  if (rootCount > 0)
    return instancesBlocked(childFirst(bvh.topRoot), rootCount, origin, direction, tFar);
  for (int node = childFirst(bvh.topRoot); node >= 0;) {
    NodeVisit visit = visitNode(topNodes[node], origin, inverse, tFar);
    for (int side = 0; side < 2; ++side) {
      if (visit.enter[side] < 0.0 || visit.count[side] == 0) continue;
      if (instancesBlocked(visit.first[side], visit.count[side], origin, direction, tFar))
        return true;
      visit.enter[side] = -1.0;
    }
    node = nextNode(visit, 0);
  }
  return false;
}

// Whether a VPL (at vplPosition) is visible from a surface point with unit normal `normal`, as
// the reference decides it: the ray starts a small distance off the surface (scaled to the
// scene) and stops just short of the VPL, so the light's own surface does not block it.
bool vplVisible(vec3 position, vec3 normal, vec3 vplPosition, vec3 vplNormal) {
  vec3 from = position + normal * bvh.rayOffsets.x;
  vec3 towardsVpl = vplPosition - from;
  return !bvhSegmentBlocked(from, towardsVpl, 1.0 - bvh.rayOffsets.y);
}
