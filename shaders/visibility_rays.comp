#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, third step: one invocation per shadow ray that visibility_trace.comp listed,
// setting the VPL's bit of the texel's mask word where the VPL is visible. A texel's rays are
// spread over many invocations instead of one invocation tracing them all: on hardware that runs
// invocations in lockstep (SIMD lanes, warps), a texel tracing 32 rays beside neighbours tracing
// few kept their lanes idle, and one ray per invocation keeps them busy.
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kVisibilityMaskBinding) buffer Masks { uint masks[]; };
layout(std430, binding = kShadowRayListBinding) readonly buffer RayList { uvec2 rayList[]; };
layout(std430, binding = kShadowRayListDispatchBinding) readonly buffer RayListDispatch {
  DispatchIndirect rayListDispatch;
};

#include "shadow_rays.glsl"
#include "visibility_texel.glsl"

uniform uint maskOffset;
uniform uint rayListCapacity;

void main() {
  uint index = linearInvocationIndex();
  if (index >= min(rayListDispatch.texelCount, rayListCapacity)) return;
  uvec2 ray = rayList[index];
  uint packedTexel = traceTexels[traceListOffset + ray.x];
  ivec2 texel = unpackTraceTexel(packedTexel);
  TexelSurface surface = texelSurface(texel);
  int i = int(ray.y);
  if (vplBitSet(surface.position, surface.shadowLift, surface.normal, surface.faceNormal,
                vpls[i])) {
    ivec2 size = textureSize(levelNormal, 0);
    atomicOr(masks[maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask + i / 32)],
             1u << uint(i % 32));
  }
}
