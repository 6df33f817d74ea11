#version 450 core
#extension GL_GOOGLE_include_directive : require
// The gather of one level: each listed texel sums the VPLs of the listed ranges (every VPL, or
// the lights of one kind), with the G-buffer averaged over its footprint. It stores the light
// before the albedo (sum of incident terms, which the albedo/pi multiplies at full resolution)
// and the specular reflection (the footprint shares k_s and n), plus, when asked, the sums of the
// other lights kept from an earlier dispatch at the same texel.
#include "shared.h"
#include "shading.glsl"

layout(local_size_x = kGatherGroupSize) in;

#include "linear_dispatch.glsl"

#include "gather_vpls.glsl"
layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kWorkListBinding) readonly buffer WorkList { uint texels[]; };
layout(std430, binding = kDispatchBinding) readonly buffer Dispatches {
  DispatchIndirect dispatches[];
};

layout(std430, binding = kVisibilityMaskBinding) readonly buffer Masks { uint masks[]; };
layout(std430, binding = kGatherVplRangeBinding) readonly buffer VplRanges {
  GpuVplRange vplRanges[];
};

#include "light_facing.glsl"

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D levelSpecular;
layout(binding = 3) uniform sampler2D keptDiffuse;
layout(binding = 4) uniform sampler2D keptSpecular;
layout(rgba32f, binding = 0) uniform writeonly image2D diffuseOut;
layout(rgba32f, binding = 1) uniform writeonly image2D specularOut;

uniform int level;
uniform uint workListOffset;
uniform vec3 eyePosition;
uniform int vplCount;
uniform int vplRangeCount;
// Add keptDiffuse and keptSpecular: the other lights' sums at this texel.
uniform bool addKept;
uniform bool shadows;
// The thesis's shortcut: unshadowed light times the fraction of visible VPLs (wrong for lights
// whose colour varies; kept for comparison). The range then holds every VPL.
uniform bool visibleFraction;
uniform int wordsPerMask;
uniform uint maskOffset;

// Adds VPL i's light, unshadowed, to the sums.
void addVpl(int i, vec3 position, vec3 normal, vec4 specular, vec3 towardsEye,
            inout vec3 diffuseSum, inout vec3 specularSum) {
  GpuVpl vpl = vpls[i];
  vec3 towardsLight;
  vec3 incident = vplIncident(position, normal, vpl.positionArea.xyz, vpl.normal.xyz,
                              vpl.positionArea.w, vpl.radiance.rgb, towardsLight);
  diffuseSum += incident;
  specularSum +=
      incident * phongBrdf(vec3(0.0), specular.rgb, specular.w, normal, towardsLight, towardsEye);
}

void main() {
  uint index = linearInvocationIndex();
  if (index >= dispatches[level].texelCount) return;
  uint packedTexel = texels[workListOffset + index];
  ivec2 texel = ivec2(packedTexel & 0xffffu, packedTexel >> 16);
  vec3 position = texelFetch(levelPositionDepth, texel, 0).xyz;
  vec3 normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  vec4 specular = texelFetch(levelSpecular, texel, 0);
  vec3 towardsEye = normalize(eyePosition - position);
  ivec2 size = textureSize(levelNormal, 0);
  uint maskStart = maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask);
  vec3 diffuseSum = addKept ? texelFetch(keptDiffuse, texel, 0).rgb : vec3(0.0);
  vec3 specularSum = addKept ? texelFetch(keptSpecular, texel, 0).rgb : vec3(0.0);
  int visibleCount = 0;
  for (int r = 0; r < vplRangeCount; ++r) {
    ivec4 range = vplRanges[r].range;
    // A quad light that cannot light the texel adds exact zeros (unless the visible fraction
    // counts its VPLs).
    if (range.z >= 0 && !visibleFraction && lightCannotLight(position, normal, lights[range.z]))
      continue;
    if (!shadows) {
      // A loop of its own, as in gather_naive.comp: llvmpipe runs it faster without the masks'
      // test in its body (docs/multiresolution.md, pass 3).
      for (int i = range.x; i < range.y; ++i)
        addVpl(i, position, normal, specular, towardsEye, diffuseSum, specularSum);
      continue;
    }
    // The mask read once per word of 32 VPLs, not once per VPL: llvmpipe pays for every read of
    // a storage buffer.
    for (int i = range.x; i < range.y;) {
      uint word = masks[maskStart + uint(i / 32)];
      int wordEnd = min(range.y, (i / 32 + 1) * 32);
      for (; i < wordEnd; ++i) {
        bool visible = (word & (1u << uint(i % 32))) != 0u;
        if (visible) ++visibleCount;
        if (!visible && !visibleFraction) continue;
        addVpl(i, position, normal, specular, towardsEye, diffuseSum, specularSum);
      }
    }
  }
  if (shadows && visibleFraction) {
    float fraction = float(visibleCount) / float(vplCount);
    diffuseSum *= fraction;
    specularSum *= fraction;
  }
  // w: 1 + the level, so the upsampling knows the texel is valid and where it came from.
  imageStore(diffuseOut, texel, vec4(diffuseSum, float(level + 1)));
  imageStore(specularOut, texel, vec4(specularSum, 0.0));
}
