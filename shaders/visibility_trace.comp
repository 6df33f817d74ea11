#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, second step: every listed texel works out its mask, with shadow rays
// through the voxel grid or the BVH where no bit is known without one. Bit i of its mask is 1
// when VPL i is not occluded; VPLs that cannot light the texel at all (behind it, or seen from
// the back) count as visible, so that the masks record occlusion only and the refinement is not
// triggered by the horizon.
//
// At the coarsest level (or under a parent without a mask, or one whose surface does not stand
// for the texel's: parent_surface.glsl) a texel traces every VPL. Below a parent whose
// visibility changed, it traces only the VPLs on which the parent and the parent's
// 8 neighbours disagree (all of them next to a neighbour without a mask), and takes the others
// from the parent: the same assumption that lets a texel under an unchanging parent inherit its
// whole mask, applied VPL by VPL. Across a penumbra neighbouring masks differ in a few VPLs, so
// most rays of the finer levels are not traced again (docs/shadows.md measures the saving and
// the error). The VPLs of lights that passed the clear-light test (visibility_clear.comp) are
// visible without a ray. At full resolution a texel leaves the quarters of VPLs that its
// neighbours trace to visibility_share.comp (sibling_vpls.glsl).
//
// The rays themselves are listed for visibility_rays.comp, one per invocation there; this step
// writes the bits it knows without a ray. Only when the list is full does it trace the rest of a
// word itself.
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kVisibilityMaskBinding) buffer Masks { uint masks[]; };
layout(std430, binding = kClearLightBinding) readonly buffer ClearLights { uint clearLights[]; };
// Per level: the shadow rays traced (a 64-bit count as two words, low and high) and the texels
// that traced none because every light passed the clear-light test.
layout(std430, binding = kShadowRayCountBinding) buffer ShadowRayCounts { uint shadowRays[]; };
layout(std430, binding = kShadowRayListBinding) writeonly buffer RayList { uvec2 rayList[]; };
layout(std430, binding = kShadowRayListDispatchBinding) buffer RayListDispatch {
  DispatchIndirect rayListDispatch;
};

#include "shadow_rays.glsl"
#include "visibility_texel.glsl"
#include "parent_surface.glsl"
#include "sibling_vpls.glsl"
#include "ray_listing.glsl"

uniform int vplCount;
uniform int lightCount;
uniform uint maskOffset;
// Whether visibility_clear.comp ran for this level; without it the clear-light words are stale.
uniform bool clearLightsTested;
// The mask words (word w: VPLs 32 w to 32 w + 31) this dispatch traces, firstWord to
// endWord - 1. The device profile sets how many may need traversals here (render/
// device_profile.h): on llvmpipe one word per dispatch, so that no invocation runs more than 32
// traversals, since llvmpipe ends any invocation's loops after 65535 iterations in all, which a
// texel's traversals to hundreds of VPLs would exceed. A dispatch takes more words only when the
// ray list can hold every ray it lists, so that it runs no traversal (render/visibility.cpp).
uniform int firstWord;
uniform int endWord;

void main() {
  ivec2 texel;
  bool parentMaskStands;
  if (!listedTexel(texel, parentMaskStands)) return;
  ivec2 size = textureSize(levelNormal, 0);
  uint clear = clearLightsTested ? clearLights[traceListOffset + linearInvocationIndex()] : 0u;
  uint everyLight = lightCount >= 32 ? ~0u : (1u << uint(lightCount)) - 1u;
  if (firstWord == 0 && clear == everyLight) atomicAdd(shadowRays[3 * level + 2], 1u);
  TexelSurface surface = texelSurface(texel);
  uint fromNeighbours = givenVpls(givingNeighboursOfEntry(texel, firstWord == 0));

  for (int word = firstWord; word < endWord; ++word) {
    int vplsInWord = clamp(vplCount - word * 32, 0, 32);
    uint toTrace = vplsInWord == 32 ? ~0u : (1u << uint(vplsInWord)) - 1u;
    uint bits = 0u;
    if (parentMaskStands) {
      uint inherited = parentWord(texel / 2, word);
      uint disagreeing = parentNeighbourhoodDisagreement(texel, word, inherited);
      toTrace &= disagreeing;
      bits = inherited & ~disagreeing;
    }
    uint clearVpls = toTrace & vplsOfLightsInWord(clear, word);
    bits |= clearVpls;
    // The neighbours that trace these give them (visibility_share.comp).
    toTrace &= ~(clearVpls | fromNeighbours);

    bits |= listOrTraceRays(toTrace, word, surface);
    masks[maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask + word)] = bits;
  }
}
