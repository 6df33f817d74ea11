#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, second step: every listed texel traces shadow rays through the voxel grid.
// Bit i of its mask is 1 when VPL i is not occluded; VPLs that cannot light the texel at all
// (behind it, or seen from the back) count as visible, so that the masks record occlusion only
// and the refinement is not triggered by the horizon.
//
// At the coarsest level (or under a parent without a mask) a texel traces every VPL. Below a
// parent whose visibility changed, it traces only the VPLs on which the parent and the parent's
// 8 neighbours disagree, and takes the others from the parent: the same assumption that lets a
// texel under an unchanging parent inherit its whole mask, applied VPL by VPL. Across a
// penumbra neighbouring masks differ in a few VPLs, so most rays of the finer levels are not
// traced again (docs/shadows.md measures the saving and the error).
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = kVisibilityMaskBinding) buffer Masks { uint masks[]; };
layout(std430, binding = kTraceListBinding) readonly buffer TraceList { uint traceTexels[]; };
layout(std430, binding = kTraceDispatchBinding) readonly buffer TraceDispatches {
  DispatchIndirect traceDispatches[];
};
layout(std430, binding = kShadowRayCountBinding) buffer ShadowRayCounts { uint shadowRays[]; };

#include "shadow_rays.glsl"

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D levelShadowLift;
layout(binding = 3) uniform sampler2D levelFaceNormal;
layout(r32ui, binding = 1) uniform readonly uimage2D parentFlags;

uniform int level;
uniform bool hasParent;
uniform int vplCount;
uniform int wordsPerMask;
uniform uint maskOffset;
uniform uint parentMaskOffset;
uniform uint traceListOffset;
// The mask words (word w: VPLs 32 w to 32 w + 31) this dispatch traces, firstWord to
// endWord - 1. The device profile sets how many (render/device_profile.h): on llvmpipe one word
// per dispatch, so that no invocation runs more than 32 traversals, since llvmpipe ends any
// invocation's loops after 65535 iterations in all, which a texel's traversals to hundreds of
// VPLs would exceed.
uniform int firstWord;
uniform int endWord;

uint parentWord(ivec2 parentTexel, ivec2 parentSize, int word) {
  return masks[parentMaskOffset +
               uint((parentTexel.y * parentSize.x + parentTexel.x) * wordsPerMask + word)];
}

bool parentHasMask(ivec2 parentTexel, ivec2 parentSize) {
  return all(greaterThanEqual(parentTexel, ivec2(0))) && all(lessThan(parentTexel, parentSize)) &&
         (imageLoad(parentFlags, parentTexel).x & kVisibilityHasMask) != 0u;
}

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= traceDispatches[level].texelCount) return;
  uint packedTexel = traceTexels[traceListOffset + index];
  ivec2 texel = ivec2(packedTexel & 0xffffu, packedTexel >> 16);
  ivec2 size = textureSize(levelNormal, 0);

  for (int word = firstWord; word < endWord; ++word) {
    int vplsInWord = clamp(vplCount - word * 32, 0, 32);
    uint toTrace = vplsInWord == 32 ? ~0u : (1u << uint(vplsInWord)) - 1u;
    uint bits = 0u;
    ivec2 parentSize = imageSize(parentFlags);
    if (hasParent && parentHasMask(texel / 2, parentSize)) {
      uint inherited = parentWord(texel / 2, parentSize, word);
      uint disagreeing = 0u;
      for (int n = 0; n < 9; ++n) {
        ivec2 neighbour = texel / 2 + ivec2(n % 3 - 1, n / 3 - 1);
        if (n != 4 && parentHasMask(neighbour, parentSize))
          disagreeing |= inherited ^ parentWord(neighbour, parentSize, word);
      }
      toTrace &= disagreeing;
      bits = inherited & ~disagreeing;
    }

    if (toTrace != 0u) {
      uint rays = uint(bitCount(toTrace));
      uint before = atomicAdd(shadowRays[2 * level], rays);
      if (before + rays < before) atomicAdd(shadowRays[2 * level + 1], 1u);
    }

    vec3 position = texelFetch(levelPositionDepth, texel, 0).xyz;
    vec3 normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
    vec3 shadowLift = texelFetch(levelShadowLift, texel, 0).xyz;
    vec3 faceNormal = texelFetch(levelFaceNormal, texel, 0).xyz;
    while (toTrace != 0u) {
      int bit = findLSB(toTrace);
      toTrace &= toTrace - 1u;
      int i = word * 32 + bit;
      vec3 towardsVpl = vpls[i].positionArea.xyz - position;
      bool canLight = dot(towardsVpl, normal) > 0.0 && dot(towardsVpl, vpls[i].normal.xyz) < 0.0;
      if (!canLight || surfacePointSeesVpl(position, shadowLift, normal, faceNormal,
                                           vpls[i].positionArea.xyz, vpls[i].normal.xyz))
        bits |= 1u << uint(bit);
    }
    masks[maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask + word)] = bits;
  }
}
