#version 450 core
#extension GL_GOOGLE_include_directive : require
// Test kernel: answers queries on a voxel grid through shaders/voxel_grid.glsl, for
// tests/render/traversal_test.cpp and shadows_test.cpp. Loaded with the renderer's shader
// directory, so the includes are the renderer's own files.
//   kQuerySegment:     query i = is the segment from ends[2i] to ends[2i+1] blocked?
//   kQuerySegmentByColumns: the same through the exact traversal's column walk alone, without
//                      skipping the occupancy pyramid's cells
//   kQueryVisibility:  query i = is VPL i % vplCount visible from point i / vplCount
//                      (ends[2p] its position, ends[2p+1] its normal)?
//   kQueryCoordinates: query i = grid coordinates of the point ends[i]
//   kQueryClearLight:  query i = does the clear-light test pass from point i (ends[2i] its
//                      position, ends[2i+1] its normal) to the quad whose corners are
//                      ends[2 queryCount] to ends[2 queryCount + 3], emitting along
//                      ends[2 queryCount + 4]?
#include "shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) readonly buffer Voxels { uint voxels[]; };

#include "light_pyramid.glsl"
#include "voxel_grid.glsl"

layout(std430, binding = 11) readonly buffer Ends { vec4 ends[]; };
layout(std430, binding = 12) writeonly buffer Answers { vec4 answers[]; };

const int kQuerySegment = 0;
const int kQueryVisibility = 1;
const int kQueryCoordinates = 2;
const int kQueryClearLight = 3;
const int kQuerySegmentByColumns = 4;

uniform int query;
uniform uint queryCount;
uniform int vplCount;

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= queryCount) return;
  vec4 answer = vec4(0.0);
  if (query == kQuerySegment) {
    answer.x = segmentBlocked(ends[2u * index].xyz, ends[2u * index + 1u].xyz) ? 1.0 : 0.0;
  } else if (query == kQuerySegmentByColumns) {
    answer.x =
        segmentBlockedDda(ends[2u * index].xyz, ends[2u * index + 1u].xyz, false) ? 1.0 : 0.0;
  } else if (query == kQueryVisibility) {
    uint point = index / uint(vplCount);
    GpuVpl vpl = vpls[index % uint(vplCount)];
    answer.x = vplVisible(ends[2u * point].xyz, ends[2u * point + 1u].xyz, vpl.positionArea.xyz,
                          vpl.normal.xyz)
                   ? 1.0
                   : 0.0;
  } else if (query == kQueryClearLight) {
    uint quad = 2u * queryCount;
    vec3 corners[4] = vec3[4](ends[quad].xyz, ends[quad + 1u].xyz, ends[quad + 2u].xyz,
                              ends[quad + 3u].xyz);
    answer.x = lightClearFrom(ends[2u * index].xyz, ends[2u * index + 1u].xyz, corners,
                              ends[quad + 4u].xyz)
                   ? 1.0
                   : 0.0;
  } else {
    answer.xyz = gridCoordinates(ends[index].xyz);
  }
  answers[index] = answer;
}
