// What answers a shader's shadow queries, vplVisible(position, normal, vplPosition, vplNormal):
// the voxel grid (voxel_grid.glsl), or, in the programs compiled with PENUMBRA_BVH_VISIBILITY
// defined (--visibility bvh, src/render/shadow_rays.h), the exact hierarchy (bvh.glsl).
// Include after shared.h. A G-buffer point asks surfacePointSeesVpl, which starts the ray where
// the reference does.
// Included here rather than by each method's file: the runtime's include expansion reads every
// #include once, whatever #ifdef it stands under (gl/program.cpp).
#include "light_pyramid.glsl"
#ifdef PENUMBRA_BVH_VISIBILITY
#include "bvh.glsl"
#else
// The grid's description is a uniform block, not a storage buffer: the traversal reads it in
// every step of its divergent loops, and as a storage buffer it made the visibility passes a few
// per cent slower on llvmpipe (docs/shadows.md, "The grid's description in a uniform block").
layout(std140, binding = kVoxelGridBinding) uniform Grid { GpuVoxelGrid grid; };
layout(std430, binding = kVoxelBinding) readonly buffer Voxels { uint voxels[]; };
#include "voxel_grid.glsl"
#endif

// Whether a VPL is visible from a G-buffer point (or a coarse texel's average of them): the ray
// starts from the point lifted onto the surface its smooth normals describe (position + lift,
// Hanika 2021, as the reference), off the surface along the triangle's face normal through the
// BVH as the reference does; the voxels' offset stays along the shading normal, whose voxel
// layer voxel_grid.glsl measures.
bool surfacePointSeesVpl(vec3 position, vec3 lift, vec3 normal, vec3 faceNormal,
                         vec3 vplPosition, vec3 vplNormal) {
#ifdef PENUMBRA_BVH_VISIBILITY
  return vplVisibleFrom(position + lift, faceNormal, vplPosition);
#else
  return vplVisible(position + lift, normal, vplPosition, vplNormal);
#endif
}

// The clear-light test from a G-buffer point (or texel) to a quad light, with the ends of
// surfacePointSeesVpl's rays: whether no shadow ray to any of its VPLs can be blocked
// (light_pyramid.glsl), so that all of them are visible without a ray.
bool surfacePointSeesLightWhole(vec3 position, vec3 lift, vec3 normal, vec3 faceNormal,
                                vec3 lightCorners[4], vec3 lightNormal) {
#ifdef PENUMBRA_BVH_VISIBILITY
  return bvhLightClearFrom(position + lift, faceNormal, lightCorners);
#else
  return lightClearFrom(position + lift, normal, lightCorners, lightNormal);
#endif
}

// The bit of a visibility mask for a VPL and a G-buffer point: set when the VPL is visible, and
// when it cannot light the point at all (behind its tangent plane, or the point behind the VPL),
// so that the masks record occlusion only and the refinement is not triggered by the horizon.
bool vplBitSet(vec3 position, vec3 lift, vec3 normal, vec3 faceNormal, GpuVpl vpl) {
  vec3 towardsVpl = vpl.positionArea.xyz - position;
  bool canLight = dot(towardsVpl, normal) > 0.0 && dot(towardsVpl, vpl.normal.xyz) < 0.0;
  return !canLight || surfacePointSeesVpl(position, lift, normal, faceNormal,
                                          vpl.positionArea.xyz, vpl.normal.xyz);
}
