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

// Whether the ray origin + t * direction, t in [0, tFar], passes through the box; `inverse` is
// 1 / direction (infinite along an axis it does not move on).
bool rayMeetsBox(vec3 origin, vec3 inverse, float tFar, vec3 boxMin, vec3 boxMax) {
  vec3 toMin = (boxMin - origin) * inverse;
  vec3 toMax = (boxMax - origin) * inverse;
  vec3 near = min(toMin, toMax);
  vec3 far = max(toMin, toMax);
  float enter = max(max(near.x, near.y), max(near.z, 0.0));
  float leave = min(min(far.x, far.y), min(far.z, tFar));
  return enter <= leave;
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
// parameter as in the world: the transform is affine).
bool bottomLevelBlocked(int root, vec3 origin, vec3 direction, float tFar) {
  vec3 inverse = safeInverse(direction);
  int stack[kBvhStackSize];
  int depth = 0;
  int node = root;
  while (true) {
    BvhNode current = nodes[node];
    int first = floatBitsToInt(current.boundsMin.w);
    int count = floatBitsToInt(current.boundsMax.w);
    bool descend = rayMeetsBox(origin, inverse, tFar, current.boundsMin.xyz, current.boundsMax.xyz);
    if (descend && count > 0) {
      for (int i = first; i < first + count; ++i)
        if (rayMeetsTriangle(origin, direction, tFar, triangles[i])) return true;
      descend = false;
    }
    if (descend) {
      // The child nearer the origin first: it is the likelier to block.
      vec3 axis = abs(current.boundsMax.xyz - current.boundsMin.xyz);
      int split = axis.x >= max(axis.y, axis.z) ? 0 : (axis.y >= axis.z ? 1 : 2);
      bool secondFirst = direction[split] < 0.0;
      stack[depth++] = secondFirst ? first : first + 1;
      node = secondFirst ? first + 1 : first;
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
    if (rayMeetsBox(origin, inverse, tFar, current.boundsMin.xyz, current.boundsMax.xyz)) {
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
