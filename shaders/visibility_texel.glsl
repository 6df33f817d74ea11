// A texel of a level's trace list, for the steps that work on it (visibility_clear.comp,
// visibility_trace.comp): where it is, its surface, and whether its parent holds a mask. Include
// after shared.h.
layout(std430, binding = kTraceListBinding) readonly buffer TraceList { uint traceTexels[]; };
layout(std430, binding = kTraceDispatchBinding) readonly buffer TraceDispatches {
  DispatchIndirect traceDispatches[];
};

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D levelShadowLift;
layout(binding = 3) uniform sampler2D levelFaceNormal;
layout(r32ui, binding = 1) uniform readonly uimage2D parentFlags;

uniform int level;
uniform bool hasParent;
uniform uint traceListOffset;

// The texel of this invocation's entry of the list; false past the list's end.
bool listedTexel(out ivec2 texel) {
  uint index = gl_GlobalInvocationID.x;
  if (index >= traceDispatches[level].texelCount) return false;
  uint packedTexel = traceTexels[traceListOffset + index];
  texel = ivec2(packedTexel & 0xffffu, packedTexel >> 16);
  return true;
}

struct TexelSurface {
  vec3 position;
  vec3 normal;  // unit
  vec3 shadowLift;
  vec3 faceNormal;
};

TexelSurface texelSurface(ivec2 texel) {
  TexelSurface surface;
  surface.position = texelFetch(levelPositionDepth, texel, 0).xyz;
  surface.normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  surface.shadowLift = texelFetch(levelShadowLift, texel, 0).xyz;
  surface.faceNormal = texelFetch(levelFaceNormal, texel, 0).xyz;
  return surface;
}

bool parentHasMask(ivec2 parentTexel) {
  ivec2 parentSize = imageSize(parentFlags);
  return all(greaterThanEqual(parentTexel, ivec2(0))) && all(lessThan(parentTexel, parentSize)) &&
         (imageLoad(parentFlags, parentTexel).x & kVisibilityHasMask) != 0u;
}
