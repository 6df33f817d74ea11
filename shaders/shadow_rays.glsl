// What answers a shader's shadow queries, vplVisible(position, normal, vplPosition, vplNormal):
// the voxel grid (voxel_grid.glsl), or, in the programs compiled with PENUMBRA_BVH_VISIBILITY
// defined (--visibility bvh, src/render/shadow_rays.h), the exact hierarchy (bvh.glsl).
// Include after shared.h.
#ifdef PENUMBRA_BVH_VISIBILITY
#include "bvh.glsl"
#else
layout(std430, binding = kVoxelGridBinding) readonly buffer Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) readonly buffer Voxels { uint voxels[]; };
#include "voxel_grid.glsl"
#endif
