#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility at the finest level, after the trace's rays: each listed texel fills in the
// quarters of VPLs that its neighbours trace for it (sibling_vpls.glsl), among the VPLs it would
// trace (every VPL, or those on which its parent's neighbourhood disagrees) that no clear light
// covers: the bits visibility_trace.comp left unset. Where the giving neighbours and the texel's
// own VPLs on either side agree on a VPL the texel takes their bit; elsewhere a shadow edge of
// that VPL passes near it, and the texel traces it. An invocation writes only its own texel's
// bits of other places, and reads only its neighbours' bits of their own places, which no
// invocation writes here.
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kVisibilityMaskBinding) buffer Masks { uint masks[]; };
layout(std430, binding = kClearLightBinding) readonly buffer ClearLights { uint clearLights[]; };
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

uniform uint maskOffset;
uniform int vplCount;
uniform int lightCount;
uniform bool clearLightsTested;
// The mask words this dispatch fills in, those of the trace's dispatch before it
// (visibility_trace.comp says why a dispatch takes few).
uniform int firstWord;
uniform int endWord;

uint maskWordIndex(ivec2 texel, int word) {
  return maskOffset + uint((texel.y * imageSize(levelFlags).x + texel.x) * wordsPerMask + word);
}

void main() {
  ivec2 texel;
  bool parentMaskStands;
  if (!listedTexel(texel, parentMaskStands)) return;
  uint giving = givingNeighboursOfEntry(texel, false);
  if (giving == 0u) return;
  uint clear = clearLightsTested ? clearLights[traceListOffset + linearInvocationIndex()] : 0u;
  uint everyLight = lightCount >= 32 ? ~0u : (1u << uint(lightCount)) - 1u;
  if (clear == everyLight) return;
  TexelSurface surface = texelSurface(texel);
  for (int word = firstWord; word < endWord; ++word) {
    int vplsInWord = clamp(vplCount - word * 32, 0, 32);
    uint pending = (vplsInWord == 32 ? ~0u : (1u << uint(vplsInWord)) - 1u) &
                   ~vplsOfLightsInWord(clear, word);
    if (parentMaskStands)
      pending &= parentNeighbourhoodDisagreement(texel, word, parentWord(texel / 2, word));
    uint traced = masks[maskWordIndex(texel, word)];
    uint own = traced & vplsOfPlace(placeInBlock(texel));
    uint given = 0u;
    uint toTrace = 0u;
    for (uint place = 0u; place < 4u; ++place) {
      uint candidates = (giving >> (4u * place)) & 0xfu;
      if (candidates == 0u) continue;
      uint seenByAll = ~0u;
      uint seenByAny = 0u;
      for (int candidate = 0; candidate < 4; ++candidate) {
        if ((candidates & (1u << uint(candidate))) == 0u) continue;
        uint neighbourBits = masks[maskWordIndex(candidateTexel(texel, place, candidate), word)];
        seenByAll &= neighbourBits;
        seenByAny |= neighbourBits;
      }
      // The texel's own VPLs on either side (4k + its place, and the same of the next or the
      // last four) moved onto the bits of this place.
      int shift = int(place) - int(placeInBlock(texel));
      uint ownSame = shift > 0 ? own << uint(shift) : own >> uint(-shift);
      uint ownOther = shift > 0 ? own >> uint(4 - shift) : own << uint(4 + shift);
      uint allVisible = seenByAll & ownSame & ownOther;
      uint allOccluded = ~seenByAny & ~ownSame & ~ownOther;
      uint quarter = vplsOfPlace(place) & pending;
      given |= allVisible & quarter;
      toTrace |= quarter & ~(allVisible | allOccluded);
    }
    given |= listOrTraceRays(toTrace, word, surface);
    masks[maskWordIndex(texel, word)] = traced | given;
  }
}
