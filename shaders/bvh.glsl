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

// Any hit in one bottom level, the ray already in its object's coordinates (t is the same
// parameter as in the world: the transform is affine). Each step tests both children of an
// inner node and goes on into the one the ray enters first (the likelier to block), keeping the
// other for later.
bool bottomLevelBlocked(int root, vec3 origin, vec3 direction, float tFar) {
  vec3 inverse = safeInverse(direction);
  BvhNode rootNode = nodes[root];
  if (rayEntersBox(origin, inverse, tFar, rootNode.boundsMin.xyz, rootNode.boundsMax.xyz) < 0.0)
    return false;
  int stack[kBvhStackSize];
  int depth = 0;
  int node = root;
  while (true) {
    BvhNode current = nodes[node];
    int first = floatBitsToInt(current.boundsMin.w);
    int count = floatBitsToInt(current.boundsMax.w);
    if (count > 0) {
      for (int i = first; i < first + count; ++i)
        if (rayMeetsTriangle(origin, direction, tFar, triangles[i])) return true;
      if (depth == 0) return false;
      node = stack[--depth];
      continue;
    }
    BvhNode left = nodes[first];
    BvhNode right = nodes[first + 1];
    float enterLeft = rayEntersBox(origin, inverse, tFar, left.boundsMin.xyz, left.boundsMax.xyz);
    float enterRight =
        rayEntersBox(origin, inverse, tFar, right.boundsMin.xyz, right.boundsMax.xyz);
    if (enterLeft >= 0.0 && enterRight >= 0.0) {
      bool leftFirst = enterLeft <= enterRight;
      stack[depth++] = leftFirst ? first + 1 : first;
      node = leftFirst ? first : first + 1;
    } else if (enterLeft >= 0.0) {
      node = first;
    } else if (enterRight >= 0.0) {
      node = first + 1;
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
    int first = floatBitsToInt(current.boundsMin.w);
    int count = floatBitsToInt(current.boundsMax.w);
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
        if (bottomLevelBlocked(instance.root.x, objectOrigin, objectDirection, tFar)) return true;
      }
    }
    if (depth == 0) return false;
    node = stack[--depth];
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
