#version 450 core
#extension GL_GOOGLE_include_directive : require
// Bitmask visibility, second step: every listed texel traces a shadow ray to every VPL through
// the voxel grid. Bit i of its mask is 1 when VPL i is not occluded; VPLs that cannot light the
// texel at all (behind it, or seen from the back) count as visible, so that the masks record
// occlusion only and the refinement is not triggered by the horizon.
#include "shared.h"

layout(local_size_x = kGatherGroupSize) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = kVoxelGridBinding) readonly buffer Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) readonly buffer Voxels { uint voxels[]; };
layout(std430, binding = kVisibilityMaskBinding) writeonly buffer Masks { uint masks[]; };
layout(std430, binding = kTraceListBinding) readonly buffer TraceList { uint traceTexels[]; };
layout(std430, binding = kTraceDispatchBinding) readonly buffer TraceDispatches {
  DispatchIndirect traceDispatches[];
};

#include "voxel_grid.glsl"

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;

uniform int level;
uniform int vplCount;
uniform int wordsPerMask;
uniform uint maskOffset;
uniform uint traceListOffset;
// The mask word (VPLs 32 word to 32 word + 31) this dispatch traces. One dispatch per word, so
// that no invocation runs more than 32 traversals: llvmpipe ends any invocation's loops after
// 65535 iterations in all, which a texel's traversals to hundreds of VPLs would exceed.
uniform int word;

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= traceDispatches[level].texelCount) return;
  uint packedTexel = traceTexels[traceListOffset + index];
  ivec2 texel = ivec2(packedTexel & 0xffffu, packedTexel >> 16);
  ivec2 size = textureSize(levelNormal, 0);
  vec3 position = texelFetch(levelPositionDepth, texel, 0).xyz;
  vec3 normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  uint bits = 0u;
  for (int bit = 0; bit < 32; ++bit) {
    int i = word * 32 + bit;
    if (i >= vplCount) break;
    vec3 towardsVpl = vpls[i].positionArea.xyz - position;
    bool canLight = dot(towardsVpl, normal) > 0.0 && dot(towardsVpl, vpls[i].normal.xyz) < 0.0;
    if (!canLight || vplVisible(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz))
      bits |= 1u << uint(bit);
  }
  masks[maskOffset + uint((texel.y * size.x + texel.x) * wordsPerMask + word)] = bits;
}
