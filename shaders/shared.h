// Buffer layouts, binding points and constants shared by C++ and GLSL (std430 layouts).
// Every struct is made of 16-byte members so that C++ and std430 agree without padding rules.
#ifdef __cplusplus
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
#define PENUMBRA_CONSTANT(type, name, value) inline constexpr type name = value
#else
#define PENUMBRA_CONSTANT(type, name, value) const type name = value
#endif

// One virtual point light on an area light.
struct GpuVpl {
  vec4 positionArea;  // xyz world position, w area A/N
  vec4 normal;        // xyz unit normal on the emitting side
  vec4 radiance;      // rgb mean radiance of the VPL's cell
};

// One area light: a quad, or a mesh light (vplInfo.w = 1) whose VPLs are made on the CPU.
struct GpuLight {
  vec4 corners[4];  // xyz of pos1..pos4; a mesh light: corners[0] and [1] its bounds' min, max
  vec4 normalArea;  // xyz unit normal on the emitting side (a mesh light: mean normal), w area
  vec4 emission;    // rgb emission scale E
  ivec4 vplInfo;    // x first VPL index, y cells per side, z 1 when textured, w 1 for a mesh
};

// Binding points of shader storage buffers.
PENUMBRA_CONSTANT(int, kVplBinding, 0);
// The gathers read the VPLs from a uniform block where all of them fit in one
// (gather_vpls.glsl): this many, 48 KiB (GL guarantees blocks of 16 KiB; llvmpipe and GPUs take
// 64 KiB), at this uniform-buffer binding.
PENUMBRA_CONSTANT(int, kVplsInUniformBlock, 1024);
PENUMBRA_CONSTANT(int, kVplUniformBlockBinding, 0);
PENUMBRA_CONSTANT(int, kLightBinding, 1);

// What a G-buffer pixel holds, stored in the w component of the normal target.
PENUMBRA_CONSTANT(int, kPixelBackground, 0);
PENUMBRA_CONSTANT(int, kPixelSurface, 1);
PENUMBRA_CONSTANT(int, kPixelEmitter, 2);

// What the refinement decided for a texel of a pyramid level (an r32ui image).
PENUMBRA_CONSTANT(uint, kTexelInvalid, 0u);   // background, light, or outside every footprint
PENUMBRA_CONSTANT(uint, kTexelComputed, 1u);  // gathered at this level
PENUMBRA_CONSTANT(uint, kTexelCovered, 2u);   // a coarser level's texel covers it: upsampled
PENUMBRA_CONSTANT(uint, kTexelRefined, 3u);   // has a discontinuity: finer levels compute it
PENUMBRA_CONSTANT(uint, kTexelUnlit, 4u);     // faces away from or lies behind every light

// Work lists: one counter and one indirect dispatch per level, texels packed as x | y << 16.
struct DispatchIndirect {
  uint groupsX;
  uint groupsY;
  uint groupsZ;
  uint texelCount;
};
PENUMBRA_CONSTANT(int, kMaxLevels, 12);
PENUMBRA_CONSTANT(int, kWorkListBinding, 2);
PENUMBRA_CONSTANT(int, kDispatchBinding, 3);
PENUMBRA_CONSTANT(int, kGatherGroupSize, 64);
// The VPLs one dispatch of the hierarchical gather sums: ranges of the VPL indices of whole
// lights. A frame that reuses the hierarchy gathers only the lights whose radiance can change (a
// video) and adds the other lights' sums it kept (docs/performance.md).
struct GpuVplRange {
  ivec4 range;  // x first VPL, y one past the last, z the light (-1: several lights), w unused
};
PENUMBRA_CONSTANT(int, kGatherVplRangeBinding, 26);

PENUMBRA_CONSTANT(float, kPi, 3.14159265358979f);
// The cosine between a texel's normal and its parent's averaged one above which the parent's
// visibility may stand for the texel's (parent_surface.glsl): 18 degrees. Measured on the post
// grids with --visibility bvh at 256x256 against reference-vpl: 0.9 left 1.4e-4 and 2.1e-4, 0.95
// 9.0e-5 and 8.5e-5, 0.98 9.0e-5 and 7.6e-5 for more rays.
PENUMBRA_CONSTANT(float, kParentNormalAgreement, 0.95f);

// Most occupancy levels a grid has: 4096 voxels per axis (the largest grid) halve to one cell in
// 12 steps.
PENUMBRA_CONSTANT(int, kMaxOccupancyLevels, 12);
PENUMBRA_CONSTANT(uint, kEmptyCell, 0xffffffffu);
// Boxes inside the voxels (GpuVoxelGrid::occupancy): a brick is a cell of occupancy level 2, 4^3
// voxels; each voxel has a word per axis, a bit per slice. 32 slices: with 16 the hung cube
// measured 1.4e-4 against reference-vpl where 32 give 4.9e-5, with 8 3.7e-4 (docs/shadows.md).
PENUMBRA_CONSTANT(int, kVoxelBrickLevel, 2);
PENUMBRA_CONSTANT(int, kVoxelBoxSlices, 32);
// Then two words, each a slab around a plane of those surfaces: the plane's normal (grid
// coordinates, octahedral, 8 bits each for u and v) in bits 16 to 31, and a bit per slice of the
// voxel's extent along that normal (kVoxelPlaneSlices) in bits 0 to 15. 32 slices in words of
// their own measured the same on the resting objects (5.3e-4 against 5.4e-4).
PENUMBRA_CONSTANT(int, kVoxelPlaneSlices, 16);
PENUMBRA_CONSTANT(int, kVoxelContentWords, 5);
PENUMBRA_CONSTANT(int, kBrickWords, 320);  // 4^3 voxels, kVoxelContentWords each
PENUMBRA_CONSTANT(uint, kNoBrick, 0xffffffffu);

// The voxel grid: one bit per voxel, columns of 32-bit words along the grid's z axis (a world
// grid also holds them along x and y; voxel_grid.glsl describes the layout).
// World grid: an axis-aligned box over the scene, voxel (x,y,z) covers
//   boundsMin + (x,y,z) * voxelSize. Screen grid: column (x,y) is a block of screen texels,
//   z a slice of view depth between depthRange.x and depthRange.y.
struct GpuVoxelGrid {
  ivec4 resolution;       // x, y columns, z slices (a multiple of 32), w words per column
  ivec4 modes;            // x kind (kGridWorld/kGridScreen), y traversal, z steps, w widen
  vec4 boundsMin;         // world grid: box minimum; w origin offset in voxel layers
  vec4 voxelSize;         // world grid: a voxel's size; w (screen grid) its diagonal at mid depth
  vec4 depthRange;        // screen grid: x nearest, y farthest view depth
  vec4 viewForward;       // screen grid: xyz unit view direction
  vec4 eyePosition;       // screen grid: xyz camera position
  vec4 clipFromWorld[4];  // screen grid: columns of the projection * view matrix
  // World grid: an occupancy pyramid over the voxels, for the traversal's empty-space skipping
  // and the clear-light test (voxel_grid.glsl).
  // Level k (1 to occupancy.x) covers cells of 2^k voxels per side: level 1 a bit per cell, set
  // when any of its voxels is; the others a word per cell, the box of its occupied voxels or
  // kEmptyCell (voxel_grid.glsl, cellBounds). occupancyLevels[k - 1].xyz: cells per axis; .w: the
  // level's first word in `voxels`, after the columns. occupancy.x is 0 for a screen grid (and
  // with --widen).
  // Boxes inside the voxels (a world grid with an occupancy level 2): each occupied cell of level
  // 2 (a brick of 4^3 voxels) has a brick in the pool, which holds for each of its voxels the
  // slices (kVoxelBoxSlices per axis) that the surfaces inside it cover, one word per axis, and
  // two slabs around planes of them, so that the traversal tests that content instead of the
  // whole voxel (voxel_content.glsl; voxel_grid.glsl, voxelContent). occupancy.y: the first word of
  // the brick table (a word per cell of level 2: its brick, or kNoBrick), after the occupancy
  // levels and a word that counts the bricks handed out; 0 when the grid has no boxes. occupancy.z:
  // the pool's first word, after the table. occupancy.w: the pool's capacity in bricks
  // (voxelize.cpp grows it when a frame needs more).
  ivec4 occupancy;
  ivec4 occupancyLevels[kMaxOccupancyLevels];
};
PENUMBRA_CONSTANT(int, kGridWorld, 0);
PENUMBRA_CONSTANT(int, kGridScreen, 1);
PENUMBRA_CONSTANT(int, kTraversalUniform, 0);
PENUMBRA_CONSTANT(int, kTraversalDda, 1);
// The world-grid voxelization's passes (voxelize_world.comp).
PENUMBRA_CONSTANT(int, kVoxelizeSolid, 0);
PENUMBRA_CONSTANT(int, kVoxelizeSurface, 1);
PENUMBRA_CONSTANT(int, kVoxelizePlaneNormals, 2);
PENUMBRA_CONSTANT(int, kVoxelizeBoxes, 3);
// Its dispatches in each pass: every triangle (one inside a single voxel is done at once, the
// others listed), the listed ones' first tile, then their further tiles.
PENUMBRA_CONSTANT(int, kVoxelizeEveryTriangle, 0);
PENUMBRA_CONSTANT(int, kVoxelizeSpanningTriangles, 1);
PENUMBRA_CONSTANT(int, kVoxelizeFurtherTiles, 2);
PENUMBRA_CONSTANT(int, kVoxelBinding, 4);
PENUMBRA_CONSTANT(int, kVoxelGridBinding, 5);
PENUMBRA_CONSTANT(int, kGeometryVertexBinding, 6);
PENUMBRA_CONSTANT(int, kGeometryIndexBinding, 7);
// Each mesh's first vertex in the surface vertex buffer (FrameGeometry::meshFirstVertices).
PENUMBRA_CONSTANT(int, kGeometryMeshBinding, 27);
PENUMBRA_CONSTANT(int, kVisibilityMaskBinding, 8);
PENUMBRA_CONSTANT(int, kTraceListBinding, 9);
PENUMBRA_CONSTANT(int, kTraceDispatchBinding, 10);
// World voxelization: two lists of triangles, each with a DispatchIndirect for them: those that
// span more than one voxel and those that span more than one tile of columns (voxelize_world.comp).
PENUMBRA_CONSTANT(int, kTriangleListBinding, 11);
PENUMBRA_CONSTANT(int, kSpanningTriangleList, 0);
PENUMBRA_CONSTANT(int, kLargeTriangleList, 1);
// Floats per vertex of the geometry buffers (position, normal, uv), as SceneGpu uploads them.
PENUMBRA_CONSTANT(int, kFloatsPerVertex, 8);

// Animated objects (animate_vertices.comp): each one's object-space vertices (kFloatsPerVertex
// floats each, uploaded once) become its world-space vertices in the surface vertex buffer at
// every frame, so that only the objects' transforms are uploaded per frame.
struct GpuObjectTransform {
  vec4 worldFromObject[4];  // columns of worldFromObject (scene/transform.h) at the frame
  vec4 normalTransform[3];  // xyz: columns of its normal matrix (normalMatrix, scene/model.h)
};
// Where an animated object's vertices lie, uploaded once: x its first vertex in the object-space
// buffer, y its first in the surface vertex buffer, z its vertex count.
struct GpuObjectVertexRange {
  ivec4 vertices;
};
PENUMBRA_CONSTANT(int, kObjectVertexBinding, 20);
PENUMBRA_CONSTANT(int, kObjectTransformBinding, 21);
PENUMBRA_CONSTANT(int, kObjectVertexRangeBinding, 22);
PENUMBRA_CONSTANT(int, kAnimateGroupSize, 64);

// Bitmask visibility: bits of a texel's mask, one per VPL; largest VPL count with shadows.
PENUMBRA_CONSTANT(int, kMaxShadowedVpls, 1024);
// Shadow rays one compute invocation may trace on llvmpipe: it ends an invocation's loops after
// 65535 iterations in all, and a traversal takes up to a few hundred, so there passes that trace
// more rays than this per texel split them over several dispatches (the device profile,
// render/device_profile.h, sets the batch per device).
PENUMBRA_CONSTANT(int, kShadowRaysPerDispatch, 32);
// Per-texel visibility flags of a level (an r32ui image).
PENUMBRA_CONSTANT(uint, kVisibilityHasMask, 1u);
PENUMBRA_CONSTANT(uint, kVisibilityChanges, 2u);
// A surface texel that would need a mask but faces no light (visibility_select.comp): its
// neighbours count as changing visibility (visibility_compare.comp).
PENUMBRA_CONSTANT(uint, kVisibilityFacesNoLight, 4u);
// A trace-list entry (visibility_select.comp) packs the texel's x in bits 0 to 15 and y in bits
// 16 to 30, and sets this bit where the parent has a mask and its surface stands for the texel's
// (parent_surface.glsl), so that the later steps need not read both levels' surfaces again.
PENUMBRA_CONSTANT(uint, kTraceTexelParentStands, 0x80000000u);
PENUMBRA_CONSTANT(int, kRefineByXorPopcount, 0);
// Per level, the shadow rays the visibility pass traced (a 64-bit count as two words, low and
// high) and the texels that traced none because every light passed the clear-light test.
PENUMBRA_CONSTANT(int, kShadowRayCountBinding, 14);
// Per listed texel of a level, a bit per light (the first 32) that passed the clear-light test:
// all of its VPLs are visible without a ray (visibility_clear.comp).
PENUMBRA_CONSTANT(int, kClearLightBinding, 23);
PENUMBRA_CONSTANT(int, kMaxClearLightTests, 32);
// The shadow rays one dispatch of visibility_trace.comp lists for visibility_rays.comp, which
// traces one per invocation: (index in the level's trace list, VPL index) per ray, and the count
// with its indirect dispatch (a DispatchIndirect whose texelCount is the rays listed, which may
// run past the list's capacity: the trace traces those rays itself).
PENUMBRA_CONSTANT(int, kShadowRayListBinding, 24);
PENUMBRA_CONSTANT(int, kShadowRayListDispatchBinding, 25);
// Per listed texel of the finest level, the neighbours that give it their quarters of the VPLs
// (sibling_vpls.glsl): worked out by the trace's first dispatch, read by the later ones and the
// share step.
PENUMBRA_CONSTANT(int, kGivingNeighbourBinding, 28);
PENUMBRA_CONSTANT(int, kRefineByOccludedCount, 1);

// Largest VPL count per light (a 32x32 grid).
PENUMBRA_CONSTANT(int, kMaxVplsPerLight, 1024);

// Indirect light (docs/indirect.md): each light's reflective shadow map is five faces of a cube
// around its centre (the face along its normal and the four sides), laid side by side in an
// atlas, one row of faces per light; the secondary VPLs sampled from it are GpuVpls too.
PENUMBRA_CONSTANT(int, kRsmFaces, 5);
PENUMBRA_CONSTANT(int, kMaxSecondaryVpls, 4096);
// The visibility of the secondary VPLs (secondary_visibility.comp): the VPLs themselves (their
// normal.w holds the index of the light whose map they came from) and two sums per VPL.
PENUMBRA_CONSTANT(int, kSecondaryVplBinding, 12);
PENUMBRA_CONSTANT(int, kSecondarySumsBinding, 13);
// Interleaved sampling of the secondary VPLs (secondary_gather.glsl): a receiver of the
// hierarchical gather takes one of this many subsets, chosen by its parity in x and y, so that the
// four texels (or pixels) of a 2x2 block take them all.
PENUMBRA_CONSTANT(int, kInterleavedSubsets, 4);
// Through the voxel grid, the bounce's second leg traces one shadow ray per this many consecutive
// secondary VPLs of a receiver's subset, which lie close together in the VPLs' cluster order
// (sampleSecondaryVpls), and counts its answer for all of them (secondary_gather.glsl).
PENUMBRA_CONSTANT(int, kSecondaryVplsPerShadowRay, 4);
// Clusters of a subset in one dispatch of the voxel programs' gather: one bit each in a word of
// shared memory (gather_indirect.comp).
PENUMBRA_CONSTANT(int, kSecondaryClustersPerDispatch, 32);
// The indirect upsampling gathers a pixel exactly when its coarse neighbours that agree with its
// geometry carry less than this fraction of the bilinear weight.
PENUMBRA_CONSTANT(float, kIndirectRefineBelow, 0.5f);

// Exact visibility (--visibility bvh, bvh.glsl): a bounding volume hierarchy per object, over
// its triangles in the object's own coordinates, built once; and a top level over the objects'
// instances (their world transforms), rebuilt when a transform changes. In both levels an inner
// node's children are nodes `first` and `first + 1`; a leaf (count > 0) holds `count` triangles
// (bottom level) or instances (top level) from `first` on. Indices are absolute in their buffer:
// every object's nodes and triangles are concatenated.
//
// The top level's nodes: boxes in world coordinates.
struct BvhNode {
  vec4 boundsMin;  // xyz; w the bits of `first` (an int)
  vec4 boundsMax;  // xyz; w the bits of `count` (an int): 0 for an inner node
};
// The bottom levels' nodes, in half a BvhNode's bytes (reading nodes is most of a shadow ray's
// time on llvmpipe, docs/shadows.md): the box in whole steps of its object's node grid
// (BvhInstance::nodeGrid), rounded outwards by at least one step, 16 bits per bound;
//   words.x = low.x | low.y << 16, words.y = low.z | high.x << 16,
//   words.z = high.y | high.z << 16,
//   words.w = first << kBvhCompactCountBits | count.
struct BvhCompactNode {
  uvec4 words;
};
PENUMBRA_CONSTANT(uint, kBvhCompactCountBits, 4u);
// A triangle as a corner and two edges (Moller-Trumbore), in its object's coordinates.
struct BvhTriangle {
  vec4 corner;
  vec4 edge1;
  vec4 edge2;
};
// One object in the world: the rows of its object-from-world affine transform, its bottom
// level's root node, and the grid its bottom level's boxes are given in: an object point p lies
// at (p - nodeGrid.xyz) / nodeGrid.w in grid steps.
struct BvhInstance {
  vec4 objectFromWorld[3];
  ivec4 root;  // x root node index in the bottom-level node buffer
  vec4 nodeGrid;
};
struct BvhHeader {
  ivec4 counts;     // x instances, y top-level nodes (0: an empty scene)
  vec4 rayOffsets;  // x how far a shadow ray starts off its surface, y the fraction of the
                    // segment it stops short of the light (both as the reference's)
};
PENUMBRA_CONSTANT(int, kBvhHeaderBinding, 15);
PENUMBRA_CONSTANT(int, kBvhTopNodeBinding, 16);
PENUMBRA_CONSTANT(int, kBvhInstanceBinding, 17);
PENUMBRA_CONSTANT(int, kBvhNodeBinding, 18);
PENUMBRA_CONSTANT(int, kBvhTriangleBinding, 19);
// Nodes a traversal keeps to visit later, per level; the builder keeps every tree shallower.
PENUMBRA_CONSTANT(int, kBvhStackSize, 48);

// How the viewer's display shader (display.frag) shows a texture.
PENUMBRA_CONSTANT(int, kDisplayRadiance, 0);    // rgb * 2^exposure
PENUMBRA_CONSTANT(int, kDisplayColour, 1);      // rgb as it is
PENUMBRA_CONSTANT(int, kDisplayNormal, 2);      // xyz * 0.5 + 0.5, black where w = 0
PENUMBRA_CONSTANT(int, kDisplayScalar, 3);      // one channel through the colour map
PENUMBRA_CONSTANT(int, kDisplayLevels, 4);      // w = +-(1 + source level) in level colours
PENUMBRA_CONSTANT(int, kDisplayCategories, 5);  // an integer value as an index into a palette
PENUMBRA_CONSTANT(int, kDisplayPaletteSize, 16);

#ifdef __cplusplus
static_assert(sizeof(GpuVpl) == 48, "GpuVpl must match its std430 layout");
static_assert(sizeof(GpuLight) == 112, "GpuLight must match its std430 layout");
static_assert(sizeof(DispatchIndirect) == 16, "DispatchIndirect must match its std430 layout");
// A uniform block (std140), whose layout is std430's for a struct of vec4s and arrays of them.
static_assert(sizeof(GpuVoxelGrid) == 384, "GpuVoxelGrid must match its std140 layout");
static_assert(sizeof(BvhNode) == 32, "BvhNode must match its std430 layout");
static_assert(sizeof(BvhTriangle) == 48, "BvhTriangle must match its std430 layout");
static_assert(sizeof(BvhCompactNode) == 16, "BvhCompactNode must match its std430 layout");
static_assert(sizeof(BvhInstance) == 80, "BvhInstance must match its std430 layout");
static_assert(sizeof(BvhHeader) == 32, "BvhHeader must match its std430 layout");
static_assert(sizeof(GpuObjectTransform) == 112, "GpuObjectTransform must match its std430 layout");
static_assert(sizeof(GpuObjectVertexRange) == 16,
              "GpuObjectVertexRange must match its std430 layout");
}  // namespace penumbra::gpu
#endif
