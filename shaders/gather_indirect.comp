#version 450 core
#extension GL_GOOGLE_include_directive : require
// The indirect gather at one resolution: every surface texel sums the irradiance of the
// secondary VPLs (secondary_gather.glsl), shadowed when given shadow rays. With them the VPLs
// come in batches, one dispatch each (IndirectGatherPass; device_profile.h says why): a batch adds
// its irradiance to the texel's. It stores the irradiance, w = 1 when the texel holds a surface.
#include "shared.h"
#include "shading.glsl"
#include "shadow_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(rgba32f, binding = 0) uniform image2D irradianceImage;

#include "secondary_gather.glsl"

uniform int firstVpl;  // this dispatch's batch: VPLs firstVpl to endVpl - 1
uniform int endVpl;
// Full resolution: normal.w is the G-buffer's pixel kind; coarser levels: surface coverage.
uniform bool fullResolution;

// Whether a texel holds a surface, with its position and unit normal.
bool surfaceTexel(ivec2 texel, out vec3 position, out vec3 normal) {
  position = vec3(0.0);
  normal = vec3(0.0);
  if (any(greaterThanEqual(texel, imageSize(irradianceImage)))) return false;
  vec4 normalW = texelFetch(levelNormal, texel, 0);
  bool surface = fullResolution ? int(normalW.w) == kPixelSurface : normalW.w > 0.0;
  if (!surface || dot(normalW.xyz, normalW.xyz) <= 0.0) return false;
  position = texelFetch(levelPositionDepth, texel, 0).xyz;
  normal = normalize(normalW.xyz);
  return true;
}

void store(ivec2 texel, bool surface, vec3 irradiance) {
  if (any(greaterThanEqual(texel, imageSize(irradianceImage)))) return;
  if (!surface) {
    imageStore(irradianceImage, texel, vec4(0.0));
    return;
  }
  if (firstVpl > 0) irradiance += imageLoad(irradianceImage, texel).rgb;
  imageStore(irradianceImage, texel, vec4(irradiance, 1.0));
}

#if defined(PENUMBRA_BVH_VISIBILITY) || defined(PENUMBRA_UNSHADOWED_SECOND_LEG)
void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  vec3 position;
  vec3 normal;
  bool surface = surfaceTexel(texel, position, normal);
  store(texel, surface, surface ? secondaryIrradiance(position, normal, firstVpl, endVpl, texel)
                                : vec3(0.0));
}
#else
// Through the voxel grid, one shadow ray per cluster of secondary VPLs (secondary_gather.glsl),
// and where the VPLs are interleaved the four texels of a subset within a 4x4 block (two texels
// apart) share out its clusters' rays: each traces every fourth cluster, and takes the others'
// answers from the texel that traced them, through shared memory, where that texel lies in its
// plane; where it does not, or it traced no ray (the cluster could not light it), the texel
// traces the ray itself. A texel so traces a quarter of the rays of its subset's clusters.
// Without interleaving (the naive mode) every texel traces its own.
const int kGroupTexels = 64;  // 8x8
shared vec4 groupPositions[kGroupTexels];  // w: 1 on a surface
shared vec4 groupNormals[kGroupTexels];
// Per texel, one bit per cluster of the batch (kSecondaryClustersPerDispatch at most): traced by
// it, and visible.
shared uint groupTraced[kGroupTexels];
shared uint groupVisible[kGroupTexels];

// Whether a texel two apart on the same surface (its normal within about 25 degrees, its position
// within about 6 degrees of the receiver's tangent plane) may lend the receiver its rays' answers.
bool sharesRays(vec3 position, vec3 normal, vec4 otherPosition, vec3 otherNormal) {
  vec3 offset = otherPosition.xyz - position;
  return otherPosition.w > 0.0 && dot(normal, otherNormal) > 0.9 &&
         abs(dot(offset, normal)) <= 0.1 * length(offset);
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 local = ivec2(gl_LocalInvocationID.xy);
  int self = local.x + 8 * local.y;
  vec3 position;
  vec3 normal;
  bool surface = surfaceTexel(texel, position, normal);
  VplSubset subset = subsetOf(firstVpl, texel);
  int clusters = surface ? clusterCount(subset, endVpl) : 0;
  // The texel's place among the four of its subset in its 4x4 block, and how many share.
  int sharers = interleaved ? 4 : 1;
  int place = interleaved ? ((local.x >> 1) & 1) + 2 * ((local.y >> 1) & 1) : 0;

  uint traced = 0u;
  uint visible = 0u;
  for (int k = place; k < clusters; k += sharers) {
    if (clusterIncident(position, normal, subset, endVpl, k) == vec3(0.0)) continue;
    traced |= 1u << k;
    if (clusterVisible(position, normal, subset, endVpl, k)) visible |= 1u << k;
  }
  groupPositions[self] = vec4(position, surface ? 1.0 : 0.0);
  groupNormals[self] = vec4(normal, 0.0);
  groupTraced[self] = traced;
  groupVisible[self] = visible;
  barrier();

  // The answers of the sharers that lie in the receiver's plane.
  uint known = traced;
  for (int other = 0; other < sharers; ++other) {
    if (other == place) continue;
    ivec2 at = ivec2((local.x & ~2) | ((other & 1) << 1), (local.y & ~2) | ((other >> 1) << 1));
    int index = at.x + 8 * at.y;
    if (!sharesRays(position, normal, groupPositions[index], groupNormals[index].xyz)) continue;
    known |= groupTraced[index];
    visible |= groupVisible[index];
  }
  vec3 irradiance = vec3(0.0);
  uint unknown = 0u;
  for (int k = 0; k < clusters; ++k) {
    vec3 incident = clusterIncident(position, normal, subset, endVpl, k);
    if (incident == vec3(0.0)) continue;
    if ((known & (1u << k)) == 0u)
      unknown |= 1u << k;
    else if ((visible & (1u << k)) != 0u)
      irradiance += incident;
  }
  // A loop, not a branch: llvmpipe skips a loop that no thread enters, where it runs the body of
  // an if for all threads when any takes it.
  while (unknown != 0u) {
    int k = findLSB(unknown);
    unknown &= unknown - 1u;
    if (clusterVisible(position, normal, subset, endVpl, k))
      irradiance += clusterIncident(position, normal, subset, endVpl, k);
  }
  store(texel, surface, irradiance);
}
#endif
