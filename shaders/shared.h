// Buffer layouts, binding points and constants shared by C++ and GLSL (std430 layouts).
// Every struct is made of 16-byte members so that C++ and std430 agree without padding rules.
#ifdef __cplusplus
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra::gpu {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
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

// One quad area light.
struct GpuLight {
  vec4 corners[4];  // xyz of pos1..pos4
  vec4 normalArea;  // xyz unit normal on the emitting side, w area
  vec4 emission;    // rgb emission scale E
  ivec4 vplInfo;    // x first VPL index, y cells per side, z 1 when textured, w unused
};

// Binding points of shader storage buffers.
PENUMBRA_CONSTANT(int, kVplBinding, 0);
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

PENUMBRA_CONSTANT(float, kPi, 3.14159265358979f);

// Largest VPL count per light (a 32x32 grid).
PENUMBRA_CONSTANT(int, kMaxVplsPerLight, 1024);

#ifdef __cplusplus
static_assert(sizeof(GpuVpl) == 48, "GpuVpl must match its std430 layout");
static_assert(sizeof(GpuLight) == 112, "GpuLight must match its std430 layout");
static_assert(sizeof(DispatchIndirect) == 16, "DispatchIndirect must match its std430 layout");
}  // namespace penumbra::gpu
#endif
