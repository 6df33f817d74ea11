#version 450 core
#extension GL_GOOGLE_include_directive : require
// Writes the world-space vertices of the animated objects into the surface vertex buffer: work
// group row y is animated object y, each invocation one of its vertices. The arithmetic is the
// CPU's (buildFrameGeometry, with glm's order of operations), and `precise` keeps the compiler
// from fusing or reordering it, so that a GPU-transformed vertex rounds as the CPU's would.
#include "shared.h"

layout(local_size_x = kAnimateGroupSize) in;

// The first vertex of this dispatch in every object: an object of more vertices than one
// dispatch's work groups hold takes several (scene_gpu.cpp).
uniform uint firstVertex;

layout(std430, binding = kObjectVertexBinding) readonly buffer ObjectVertices {
  float objectVertex[];
};
layout(std430, binding = kObjectTransformBinding) readonly buffer Transforms {
  GpuObjectTransform transforms[];
};
layout(std430, binding = kObjectVertexRangeBinding) readonly buffer Ranges {
  GpuObjectVertexRange ranges[];
};
layout(std430, binding = kGeometryVertexBinding) writeonly buffer SurfaceVertices {
  float surfaceVertex[];
};

vec3 readVec3(uint first) {
  return vec3(objectVertex[first], objectVertex[first + 1u], objectVertex[first + 2u]);
}

void main() {
  const uint object = gl_WorkGroupID.y;
  const ivec4 range = ranges[object].vertices;
  const uint vertex = firstVertex + gl_GlobalInvocationID.x;
  if (vertex >= uint(range.z))
    return;
  const uint source = (uint(range.x) + vertex) * uint(kFloatsPerVertex);
  const uint target = (uint(range.y) + vertex) * uint(kFloatsPerVertex);
  const vec3 position = readVec3(source);
  const vec3 objectNormal = readVec3(source + 3u);

  // glm's mat4 * vec4: (m0 x + m1 y) + (m2 z + m3 w), with w = 1.
  const vec4 m[4] = transforms[object].worldFromObject;
  precise const vec4 world = (m[0] * position.x + m[1] * position.y) + (m[2] * position.z + m[3]);
  // glm's mat3 * vec3 (left to right) and dot (x + y + z).
  const vec4 n[3] = transforms[object].normalTransform;
  precise const vec3 normal =
      n[0].xyz * objectNormal.x + n[1].xyz * objectNormal.y + n[2].xyz * objectNormal.z;
  precise const float lengthSquared = normal.x * normal.x + normal.y * normal.y + normal.z * normal.z;
  // A transform that flattens the object can collapse a normal; keep the model's then.
  precise const vec3 worldNormal = lengthSquared > 0.0 ? normal / sqrt(lengthSquared) : objectNormal;

  surfaceVertex[target] = world.x;
  surfaceVertex[target + 1u] = world.y;
  surfaceVertex[target + 2u] = world.z;
  surfaceVertex[target + 3u] = worldNormal.x;
  surfaceVertex[target + 4u] = worldNormal.y;
  surfaceVertex[target + 5u] = worldNormal.z;
  surfaceVertex[target + 6u] = objectVertex[source + 6u];
  surfaceVertex[target + 7u] = objectVertex[source + 7u];
}
