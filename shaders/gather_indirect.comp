#version 450 core
#extension GL_GOOGLE_include_directive : require
// The indirect gather at one resolution: every surface texel sums the irradiance of the
// secondary VPLs (secondary_gather.glsl), shadowed when given shadow rays. With them the VPLs
// come in batches of the device profile's shadowRaysPerDispatch, one dispatch each
// (device_profile.h says why): a batch adds its irradiance to the texel's. It stores the
// irradiance, w = 1 when the texel holds a surface.
#include "shared.h"
#include "shading.glsl"
#include "shadow_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(rgba32f, binding = 0) uniform image2D irradianceImage;

#include "secondary_gather.glsl"

uniform int firstVpl;  // this dispatch's batch: VPLs firstVpl to endVpl - 1
uniform int endVpl;
// Full resolution: normal.w is the G-buffer's pixel kind; coarser levels: surface coverage.
uniform bool fullResolution;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(irradianceImage)))) return;
  vec4 normalW = texelFetch(levelNormal, texel, 0);
  bool surface = fullResolution ? int(normalW.w) == kPixelSurface : normalW.w > 0.0;
  if (!surface || dot(normalW.xyz, normalW.xyz) <= 0.0) {
    imageStore(irradianceImage, texel, vec4(0.0));
    return;
  }
  vec3 position = texelFetch(levelPositionDepth, texel, 0).xyz;
  vec3 normal = normalize(normalW.xyz);
  vec3 irradiance = secondaryIrradiance(position, normal, firstVpl, endVpl, texel);
  if (firstVpl > 0) irradiance += imageLoad(irradianceImage, texel).rgb;
  imageStore(irradianceImage, texel, vec4(irradiance, 1.0));
}
