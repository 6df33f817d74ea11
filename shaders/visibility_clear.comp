#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, before the trace: the clear-light test (light_pyramid.glsl: through the
// voxel grid's occupancy pyramid, or through the BVH with --visibility bvh) of one quad light
// for the listed texels. Where it passes, bit `lightIndex` of the texel's clear-light word is
// set, and visibility_trace.comp takes that light's VPLs as visible without a ray. A texel under a
// parent whose mask holds the light partly occluded skips the test: it lies in or next to the
// penumbra, where the test mostly fails after descending far (on the dragon at 1024x1024 testing
// them cost more than the rays it spared). A texel whose parent and the parent's neighbours all
// see the light whole needs no test: the trace would take every VPL of it from the parent. Both
// only where the parent's surface stands for the texel's (parent_surface.glsl); elsewhere the
// texel takes the test and traces what it does not clear, as at the coarsest level. One
// dispatch per light, so that no invocation runs more than one test (llvmpipe's loop limit).
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kVisibilityMaskBinding) readonly buffer Masks { uint masks[]; };
layout(std430, binding = kClearLightBinding) buffer ClearLights { uint clearLights[]; };

#include "light_facing.glsl"
#include "shadow_rays.glsl"
#include "visibility_texel.glsl"

uniform int lightIndex;

// Whether the parent's mask holds every VPL of the light visible.
bool parentSawLightWhole(ivec2 parentTexel) {
  int first = lights[lightIndex].vplInfo.x;
  int last = first + lights[lightIndex].vplInfo.y * lights[lightIndex].vplInfo.y - 1;
  for (int word = first / 32; word <= last / 32; ++word) {
    uint bits = lightBitsInWord(lightIndex, word);
    if ((parentWord(parentTexel, word) & bits) != bits) return false;
  }
  return true;
}

// Whether each of the parent's 8 neighbours that holds a mask holds every VPL of the light
// visible.
bool neighboursSawLightWhole(ivec2 parentTexel) {
  for (int n = 0; n < 9; ++n) {
    ivec2 neighbour = parentTexel + ivec2(n % 3 - 1, n / 3 - 1);
    if (n != 4 && parentHasMask(neighbour) && !parentSawLightWhole(neighbour)) return false;
  }
  return true;
}

void main() {
  ivec2 texel;
  bool parentMaskStands;
  if (!listedTexel(texel, parentMaskStands)) return;
  if (parentMaskStands) {
    if (!parentSawLightWhole(texel / 2)) return;
    // The parent and its neighbours agree that every VPL of the light is visible, so the trace
    // takes them all from the parent without a ray (it traces only the VPLs on which those masks
    // disagree): the light is clear without the test.
    if (neighboursSawLightWhole(texel / 2)) {
      atomicOr(clearLights[traceListOffset + linearInvocationIndex()], 1u << uint(lightIndex));
      return;
    }
  }
  GpuLight light = lights[lightIndex];
  vec3 corners[4] = vec3[4](light.corners[0].xyz, light.corners[1].xyz, light.corners[2].xyz,
                            light.corners[3].xyz);
  TexelSurface surface = texelSurface(texel);
  // The same ends as the trace's rays (surfacePointSeesVpl in shadow_rays.glsl).
  if (lightCannotLight(surface.position, surface.normal, light) ||
      surfacePointSeesLightWhole(surface.position, surface.shadowLift, surface.normal,
                                 surface.faceNormal, corners, light.normalArea.xyz))
    atomicOr(clearLights[traceListOffset + linearInvocationIndex()], 1u << uint(lightIndex));
}
