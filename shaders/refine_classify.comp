#version 450 core
#extension GL_GOOGLE_include_directive : require
// Refinement at one level, from the coarsest to the finest: a texel whose parent already has a
// value is covered by it; otherwise it is computed here when its footprint has no
// discontinuity (always at level 0, for surface pixels), and refined further when it has one:
// a depth or normal discontinuity, a change of visibility between neighbours, or a footprint
// too large against its distance to a light for the light's irradiance to be interpolated.
// Computed texels are appended to this level's work list.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kWorkListBinding) writeonly buffer WorkList { uint texels[]; };
layout(std430, binding = kDispatchBinding) buffer Dispatches { DispatchIndirect dispatches[]; };

#include "light_facing.glsl"

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D levelDiscontinuity;
layout(r32ui, binding = 0) uniform readonly uimage2D parentState;
layout(r32ui, binding = 1) uniform writeonly uimage2D stateOut;
#ifndef PENUMBRA_WITHOUT_VISIBILITY_FLAGS
// Visibility flags of this level (visibility_select/compare). Frames without shadows have none, and
// run a program built without them: llvmpipe pays for the load of every texel's flag, which took a
// sixth of level 0's classification on the dragon.
layout(r32ui, binding = 2) uniform readonly uimage2D visibilityFlags;
#endif

uniform int level;
uniform bool hasParent;
uniform float depthThreshold;
uniform float normalThreshold;
// On the light proximity (discontinuity.comp) times the texel's size in pixels, 2^level.
uniform float lightProximityThreshold;
uniform int lightCount;
uniform uint workListOffset;

bool visibilityChanges(ivec2 texel) {
#ifdef PENUMBRA_WITHOUT_VISIBILITY_FLAGS
  return false;
#else
  return (imageLoad(visibilityFlags, texel).x & kVisibilityChanges) != 0u;
#endif
}

uint classify(ivec2 texel) {
  if (hasParent) {
    uint parent = imageLoad(parentState, texel / 2).x;
    if (parent == kTexelComputed || parent == kTexelCovered) return kTexelCovered;
    if (parent == kTexelUnlit) return kTexelUnlit;
  }
  vec4 discontinuity = texelFetch(levelDiscontinuity, texel, 0);
  bool holdsOtherPixels = discontinuity.b > 0.0;
  bool changes = discontinuity.r > depthThreshold || discontinuity.g > normalThreshold ||
                 discontinuity.a * float(1 << level) > lightProximityThreshold ||
                 visibilityChanges(texel);
  if (level == 0) {
    if (holdsOtherPixels) return kTexelInvalid;
  } else if (holdsOtherPixels || changes) {
    return kTexelRefined;
  }
  vec3 position = texelFetch(levelPositionDepth, texel, 0).xyz;
  vec3 normal = texelFetch(levelNormal, texel, 0).xyz;
  return facesAnyLight(position, normal, lightCount) ? kTexelComputed : kTexelUnlit;
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(stateOut)))) return;
  uint state = classify(texel);
  imageStore(stateOut, texel, uvec4(state));
  if (state == kTexelComputed) {
    uint slot = atomicAdd(dispatches[level].texelCount, 1u);
    texels[workListOffset + slot] = uint(texel.x) | (uint(texel.y) << 16);
  }
}
