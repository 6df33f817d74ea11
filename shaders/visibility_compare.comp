#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, last step: a texel's visibility changes when its mask differs from a
// 4-neighbour's by more than the threshold, measured either as the number of VPLs whose
// visibility differs (popcount of the XOR) or, as the thesis did, as the difference of the
// numbers of occluded VPLs, and when a 4-neighbour is a surface that faces no light. Such texels
// are refined like geometric discontinuities.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kVisibilityMaskBinding) readonly buffer Masks { uint masks[]; };

layout(r32ui, binding = 0) uniform uimage2D flags;

uniform int wordsPerMask;
uniform uint maskOffset;
uniform int measure;
uniform float threshold;  // in VPLs

uint maskStart(ivec2 texel, ivec2 size) {
  return maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask);
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(flags);
  if (any(greaterThanEqual(texel, size))) return;
  uint own = imageLoad(flags, texel).x;
  if ((own & kVisibilityHasMask) == 0u) return;
  const ivec2 offsets[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  uint start = maskStart(texel, size);
  bool changes = false;
  for (int n = 0; n < 4 && !changes; ++n) {
    ivec2 neighbour = texel + offsets[n];
    if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
    uint neighbourFlags = imageLoad(flags, neighbour).x;
    // A surface that faces no light has no mask to compare, but where it meets a lit one (the
    // underside of the bunny's foot on its box, a ceiling along a wall's top) the lit side's
    // contact shadow changes within a texel: taken whole from parents that saw it lit, it lost
    // its contact shadow (the bunny's box 1.4e-4 against reference-vpl, 4.7e-5 now).
    if ((neighbourFlags & kVisibilityFacesNoLight) != 0u) {
      changes = true;
      break;
    }
    if ((neighbourFlags & kVisibilityHasMask) == 0u) continue;
    uint other = maskStart(neighbour, size);
    int differing = 0;
    int visibleHere = 0;
    int visibleThere = 0;
    for (int word = 0; word < wordsPerMask; ++word) {
      uint a = masks[start + uint(word)];
      uint b = masks[other + uint(word)];
      differing += bitCount(a ^ b);
      visibleHere += bitCount(a);
      visibleThere += bitCount(b);
    }
    float difference = measure == kRefineByXorPopcount ? float(differing)
                                                       : float(abs(visibleHere - visibleThere));
    changes = difference > threshold;
  }
  // Only this texel's own flag is written; neighbours read the kVisibilityHasMask bit, which no
  // invocation changes here.
  if (changes) imageStore(flags, texel, uvec4(own | kVisibilityChanges));
}
