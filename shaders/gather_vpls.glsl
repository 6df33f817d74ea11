// The VPLs as the gathers (gather_hierarchical.comp, gather_naive.comp) read them. All the
// invocations of a gather read the same VPL at a time. From a uniform block llvmpipe loads it once
// for all its SIMD lanes, where from a storage buffer it gathers it lane by lane: the hierarchical
// gather took a fifth of the time on the demo (docs/performance.md, "VPLs read from a uniform
// block"). The block holds kVplsInUniformBlock VPLs; programs compiled with
// PENUMBRA_VPLS_IN_STORAGE_BUFFER read any number from the storage buffer instead (render/vpls.h,
// gatherVplSource, picks). Include after shared.h.
#ifdef PENUMBRA_VPLS_IN_STORAGE_BUFFER
layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
#else
layout(std140, binding = kVplUniformBlockBinding) uniform VplBlock {
  GpuVpl vpls[kVplsInUniformBlock];
};
#endif
