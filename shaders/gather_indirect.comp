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
// and where the VPLs are interleaved the texels of a subset share out its clusters' rays. The
// sixteen texels of a subset in the 8x8 workgroup (two texels apart) each find those of them that
// lie on their surface: in their tangent plane, with the image's line between them on it too.
// The clusters are dealt out in turn among the texels of one surface: each traces its share and
// takes the others' answers from the texels that traced them, through shared memory. Where the
// texels of a surface disagree about who shares (a curved surface, a texel straddling two), or
// one traced no ray for a cluster (it could not light that texel), the texel traces the ray itself.
// Without interleaving (the naive mode) every texel traces its own. On the dragon at 1024x1024 a
// texel traced about 15 rays for its 64 clusters with the four texels of a 4x4 block sharing, 12
// with all sixteen sharing out every cluster, and 6.5 like this (docs/indirect.md).
const int kSharersPerSide = 4;  // a subset's texels in the workgroup, per side
const int kGroupTexels = 64;  // 8x8
shared vec4 groupPositions[kGroupTexels];  // w: 1 on a surface
shared vec4 groupNormals[kGroupTexels];
// Per texel, one bit per cluster of the batch (kSecondaryClustersPerDispatch at most): traced by
// it, and visible.
shared uint groupTraced[kGroupTexels];
shared uint groupVisible[kGroupTexels];

// Whether a texel of the workgroup on the same surface (its normal within about 25 degrees, its
// position within about 6 degrees of the receiver's tangent plane) may lend the receiver its rays'
// answers.
bool sharesRays(vec3 position, vec3 normal, vec4 otherPosition, vec3 otherNormal) {
  vec3 offset = otherPosition.xyz - position;
  return otherPosition.w > 0.0 && dot(normal, otherNormal) > 0.9 &&
         abs(dot(offset, normal)) <= 0.1 * length(offset);
}

// The workgroup's index of the texel that takes the sharer's place `other` in the receiver's
// subset.
int sharerIndex(ivec2 local, int other) {
  ivec2 at = ivec2((local.x & 1) | ((other % kSharersPerSide) << 1),
                   (local.y & 1) | ((other / kSharersPerSide) << 1));
  return at.x + 8 * at.y;
}

// The clusters dealt to the texel of rank `rank` among `sharers`: every sharers-th from it.
uint clusterShare(int rank, int sharers, int clusters) {
  uint share = 0u;
  for (int k = rank; k < clusters; k += sharers) share |= 1u << k;
  return share;
}

// Whether every texel on the image's line from the receiver to a sharer lies on the receiver's
// surface too: two floors on either side of a wall lie in one plane, and the wall shows between
// them.
bool surfaceBetween(ivec2 local, int sharer, vec3 position, vec3 normal) {
  ivec2 step = ivec2(sharer % 8, sharer / 8) - local;
  int steps = max(abs(step.x), abs(step.y));
  for (int i = 1; i < steps; ++i) {
    ivec2 between = local + ivec2(round(vec2(step) * (float(i) / float(steps))));
    int index = between.x + 8 * between.y;
    if (!sharesRays(position, normal, groupPositions[index], groupNormals[index].xyz))
      return false;
  }
  return true;
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
  // The texel's place among the texels of its subset in the workgroup, and how many share.
  int sharers = interleaved ? kSharersPerSide * kSharersPerSide : 1;
  int place = interleaved ? (local.x >> 1) + kSharersPerSide * (local.y >> 1) : 0;

  groupPositions[self] = vec4(position, surface ? 1.0 : 0.0);
  groupNormals[self] = vec4(normal, 0.0);
  barrier();

  // The sharers on the receiver's surface, one bit per place, the receiver's own included.
  uint sameSurface = 1u << place;
  for (int other = 0; other < sharers; ++other) {
    int index = sharerIndex(local, other);
    if (other != place &&
        sharesRays(position, normal, groupPositions[index], groupNormals[index].xyz) &&
        surfaceBetween(local, index, position, normal))
      sameSurface |= 1u << other;
  }
  // Dealt out among the texels of one surface rather than the whole workgroup's: the clusters of
  // a texel on another surface would be traced again by every receiver on this one.
  int surfaceSharers = bitCount(sameSurface);
  int rank = bitCount(sameSurface & ((1u << place) - 1u));

  // The texel's own clusters are summed as they are traced; the others' wait for the sharers.
  uint own = clusterShare(rank, surfaceSharers, clusters);
  uint traced = 0u;
  uint visible = 0u;
  vec3 irradiance = vec3(0.0);
  for (int k = rank; k < clusters; k += surfaceSharers) {
    vec3 incident = clusterIncident(position, normal, subset, endVpl, k);
    if (incident == vec3(0.0)) continue;
    traced |= 1u << k;
    if (clusterVisible(position, normal, subset, endVpl, k)) {
      visible |= 1u << k;
      irradiance += incident;
    }
  }
  groupTraced[self] = traced;
  groupVisible[self] = visible;
  barrier();

  // The answers of the sharers on the receiver's surface, each for the clusters that the
  // receiver's share-out gives it: a texel whose own sharers differ (it straddles two surfaces,
  // a wall's foot between two floors) lends at most its share.
  uint known = 0u;
  for (int other = 0, otherRank = 0; other < sharers; ++other) {
    if ((sameSurface & (1u << other)) == 0u) continue;
    uint share = clusterShare(otherRank++, surfaceSharers, clusters);
    if (other == place) continue;
    int index = sharerIndex(local, other);
    known |= groupTraced[index] & share;
    visible |= groupVisible[index] & share;
  }
  // The texel's own clusters are summed already, and one a sharer found hidden adds nothing.
  uint settled = own | (known & ~visible);
  uint unknown = 0u;
  for (int k = 0; k < clusters; ++k) {
    if ((settled & (1u << k)) != 0u) continue;
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
