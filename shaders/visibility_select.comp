#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, first step of a level: which texels need a visibility mask and where it
// comes from. A texel needs one when a coarser texel does not already cover it (it is at the
// coarsest level, or its parent was refined) and it faces a light. It inherits its parent's
// mask when the parent's visibility agreed with its neighbours' and the parent's surface stands
// for its own (parent_surface.glsl); otherwise (or at the coarsest level) it is listed for
// tracing (visibility_trace.comp decides which VPLs), its entry marked where the parent stands
// for it. A pixel next to another surface that touches it (the floor at an object's foot, a wall
// where it meets the floor) takes nothing from its parent: a contact shadow can be narrower than
// a parent texel, such as the floor under a toe, dark between lit pixels, which the parent and
// its neighbours all miss. A surface texel that would need one but faces no light is flagged as
// such, for the compare step.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kVisibilityMaskBinding) buffer Masks { uint masks[]; };
layout(std430, binding = kTraceListBinding) writeonly buffer TraceList { uint traceTexels[]; };
layout(std430, binding = kTraceDispatchBinding) buffer TraceDispatches {
  DispatchIndirect traceDispatches[];
};

#include "light_facing.glsl"

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
#include "parent_surface.glsl"
// w: the pixel's mesh plus one at level 0 (the G-buffer's), 0 on coarser levels.
layout(binding = 3) uniform sampler2D levelFaceNormal;

layout(r32ui, binding = 0) uniform readonly uimage2D parentState;
layout(r32ui, binding = 1) uniform readonly uimage2D parentFlags;
layout(r32ui, binding = 2) uniform writeonly uimage2D flagsOut;

uniform int level;
uniform bool hasParent;
uniform int lightCount;
uniform int wordsPerMask;
uniform uint maskOffset;        // first word of this level's masks
uniform uint parentMaskOffset;  // first word of the parent level's masks
uniform uint traceListOffset;

// Whether one of the pixel's 4 neighbours is another mesh's surface (another object's, or a part of
// the same object with another material) within planeTolerance of the distance to the eye: where
// two surfaces touch. Only the G-buffer knows a pixel's mesh.
bool touchesAnotherMesh(ivec2 pixel, ivec2 size) {
  vec4 own = texelFetch(levelPositionDepth, pixel, 0);
  float mesh = texelFetch(levelFaceNormal, pixel, 0).w;
  const ivec2 steps[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
  for (int i = 0; i < 4; ++i) {
    ivec2 neighbour = pixel + steps[i];
    if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
    float neighbourMesh = texelFetch(levelFaceNormal, neighbour, 0).w;
    if (int(texelFetch(levelNormal, neighbour, 0).w) == kPixelSurface &&
        neighbourMesh != mesh &&
        distance(texelFetch(levelPositionDepth, neighbour, 0).xyz, own.xyz) <=
            planeTolerance * own.w)
      return true;
  }
  return false;
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(levelNormal, 0);
  if (any(greaterThanEqual(texel, size))) return;
  uint flags = 0u;
  vec4 normal = texelFetch(levelNormal, texel, 0);
  bool surface = level == 0 ? int(normal.w) == kPixelSurface : normal.w > 0.0;
  bool uncovered = !hasParent || imageLoad(parentState, texel / 2).x == kTexelRefined;
  bool needsMask = surface && uncovered;
  bool facesLight = needsMask && facesAnyLight(texelFetch(levelPositionDepth, texel, 0).xyz,
                                               normalize(normal.xyz), lightCount);
  if (needsMask && !facesLight) flags = kVisibilityFacesNoLight;
  if (facesLight) {
    flags = kVisibilityHasMask;
    uint parent = hasParent ? imageLoad(parentFlags, texel / 2).x : 0u;
    bool parentStands = (parent & kVisibilityHasMask) != 0u && parentStandsFor(texel) &&
                        !(level == 0 && touchesAnotherMesh(texel, size));
    if (parent == kVisibilityHasMask && parentStands) {
      ivec2 parentTexel = texel / 2;
      int parentWidth = (size.x + 1) / 2;
      uint from = parentMaskOffset + uint((parentTexel.y * parentWidth + parentTexel.x) *
                                          wordsPerMask);
      uint to = maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask);
      for (int word = 0; word < wordsPerMask; ++word) masks[to + uint(word)] = masks[from + uint(word)];
    } else {
      uint slot = atomicAdd(traceDispatches[level].texelCount, 1u);
      traceTexels[traceListOffset + slot] = uint(texel.x) | (uint(texel.y) << 16) |
                                            (parentStands ? kTraceTexelParentStands : 0u);
    }
  }
  imageStore(flagsOut, texel, uvec4(flags));
}
