// A texel of a level's trace list, for the steps that work on it (visibility_clear.comp,
// visibility_trace.comp): where it is, its surface, its parent's mask, and which bits of a mask
// word belong to a light. Include after shared.h and the declarations of the `lights` and
// `masks` buffers.
#include "linear_dispatch.glsl"

layout(std430, binding = kTraceListBinding) readonly buffer TraceList { uint traceTexels[]; };
layout(std430, binding = kTraceDispatchBinding) readonly buffer TraceDispatches {
  DispatchIndirect traceDispatches[];
};

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D levelShadowLift;
layout(binding = 3) uniform sampler2D levelFaceNormal;
layout(r32ui, binding = 1) uniform readonly uimage2D parentFlags;

uniform int level;
uniform uint traceListOffset;
uniform int wordsPerMask;
uniform uint parentMaskOffset;  // first word of the parent level's masks

struct TexelSurface {
  vec3 position;
  vec3 normal;  // unit
  vec3 shadowLift;
  vec3 faceNormal;
};

TexelSurface texelSurface(ivec2 texel) {
  TexelSurface surface;
  surface.position = texelFetch(levelPositionDepth, texel, 0).xyz;
  surface.normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  surface.shadowLift = texelFetch(levelShadowLift, texel, 0).xyz;
  surface.faceNormal = texelFetch(levelFaceNormal, texel, 0).xyz;
  return surface;
}

bool parentHasMask(ivec2 parentTexel) {
  ivec2 parentSize = imageSize(parentFlags);
  return all(greaterThanEqual(parentTexel, ivec2(0))) && all(lessThan(parentTexel, parentSize)) &&
         (imageLoad(parentFlags, parentTexel).x & kVisibilityHasMask) != 0u;
}

ivec2 unpackTraceTexel(uint packedTexel) {
  return ivec2(packedTexel & 0xffffu, (packedTexel & ~kTraceTexelParentStands) >> 16);
}

// The texel of this invocation's entry of the list, and whether its parent has a mask that may
// stand for its visibility (the parent's surface stands for the texel's: parent_surface.glsl);
// false past the list's end.
bool listedTexel(out ivec2 texel, out bool parentMaskStands) {
  uint index = linearInvocationIndex();
  if (index >= traceDispatches[level].texelCount) return false;
  uint packedTexel = traceTexels[traceListOffset + index];
  texel = unpackTraceTexel(packedTexel);
  parentMaskStands = (packedTexel & kTraceTexelParentStands) != 0u;
  return true;
}

uint parentWord(ivec2 parentTexel, int word) {
  return masks[parentMaskOffset + uint((parentTexel.y * imageSize(parentFlags).x + parentTexel.x) *
                                       wordsPerMask + word)];
}

// The bits of mask word `word` (VPLs 32 word to 32 word + 31) that are VPLs of `light`.
uint lightBitsInWord(int light, int word) {
  int first = lights[light].vplInfo.x - word * 32;
  int low = max(first, 0);
  int high = min(first + lights[light].vplInfo.y * lights[light].vplInfo.y, 32);
  if (low >= high) return 0u;
  return (high - low == 32 ? ~0u : (1u << uint(high - low)) - 1u) << uint(low);
}

// The bits of mask word `word` that belong to the lights set in `lightsSet` (bit per light).
uint vplsOfLightsInWord(uint lightsSet, int word) {
  uint bits = 0u;
  while (lightsSet != 0u) {
    int light = findLSB(lightsSet);
    lightsSet &= lightsSet - 1u;
    bits |= lightBitsInWord(light, word);
  }
  return bits;
}

// The VPLs of mask word `word` on which the parent's mask (`inherited`) and the masks of the
// parent's 8 neighbours disagree. A neighbour without a mask (unlit, a light, the background,
// outside the image) cannot confirm the parent's: at the foot of a box whose side faces away
// from the light, the floor's parents all agreed on the light and their texels took it, losing
// the contact shadow (the Cornell box with the bunny: 5.0e-4 against reference-vpl, 1.4e-4 now).
uint parentNeighbourhoodDisagreement(ivec2 texel, int word, uint inherited) {
  uint disagreeing = 0u;
  for (int n = 0; n < 9; ++n) {
    ivec2 neighbour = texel / 2 + ivec2(n % 3 - 1, n / 3 - 1);
    if (n == 4) continue;
    disagreeing |= parentHasMask(neighbour) ? inherited ^ parentWord(neighbour, word) : ~0u;
  }
  return disagreeing;
}
