#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, before the trace: the clear-light test (voxel_grid.glsl) of one quad light
// for every listed texel. Where it passes, bit `lightIndex` of the texel's clear-light word is
// set, and visibility_trace.comp takes that light's VPLs as visible without a ray. Texels under a
// parent whose visibility changed take the test too: most of those at a penumbra's edge see the
// whole light (on the demo at 512x512, 85 to 95% of those that see a light whole pass). One
// dispatch per light, so that no invocation runs more than one test (llvmpipe's loop limit).
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kClearLightBinding) buffer ClearLights { uint clearLights[]; };
layout(std430, binding = kVoxelGridBinding) readonly buffer Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) readonly buffer Voxels { uint voxels[]; };

#include "voxel_grid.glsl"
#include "visibility_texel.glsl"

uniform int lightIndex;

// Whether no VPL of the quad can light the point, so that the trace counts all of them visible
// without a ray (its canLight): the quad lies behind the point's tangent plane, or the point
// behind the quad's emitting side. Both hold for every VPL when they hold for the corners, of
// which the VPLs are convex combinations; a margin of 1e-4 of the distance keeps the VPLs'
// rounding from tipping a corner case (a point in the light's plane) the other way.
bool lightCannotLight(vec3 position, vec3 normal, vec3 corners[4], vec3 lightNormal) {
  bool behindPoint = true;
  bool pointBehindLight = true;
  for (int i = 0; i < 4; ++i) {
    vec3 towardsCorner = corners[i] - position;
    float margin = 1e-4 * length(towardsCorner);
    behindPoint = behindPoint && dot(towardsCorner, normal) < -margin;
    pointBehindLight = pointBehindLight && dot(towardsCorner, lightNormal) > margin;
  }
  return behindPoint || pointBehindLight;
}

void main() {
  ivec2 texel;
  if (!listedTexel(texel)) return;
  GpuLight light = lights[lightIndex];
  vec3 corners[4] = vec3[4](light.corners[0].xyz, light.corners[1].xyz, light.corners[2].xyz,
                            light.corners[3].xyz);
  TexelSurface surface = texelSurface(texel);
  // The same ends as the trace's rays (surfacePointSeesVpl in shadow_rays.glsl).
  if (lightCannotLight(surface.position, surface.normal, corners, light.normalArea.xyz) ||
      lightClearFrom(surface.position + surface.shadowLift, surface.normal, corners,
                     light.normalArea.xyz))
    atomicOr(clearLights[traceListOffset + gl_GlobalInvocationID.x], 1u << uint(lightIndex));
}
