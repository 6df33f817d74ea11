#version 450 core
#extension GL_GOOGLE_include_directive : require
// The indirect gather at one resolution: every surface texel sums the irradiance of every
// secondary VPL, with the bounded form factor of the primary VPLs and no visibility (the
// indirect light is unshadowed; docs/indirect.md). It stores the irradiance, w = 1 when the
// texel holds a surface.
#include "shared.h"
#include "shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(rgba32f, binding = 0) uniform writeonly image2D irradianceOut;

uniform int vplCount;
// Full resolution: normal.w is the G-buffer's pixel kind; coarser levels: surface coverage.
uniform bool fullResolution;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(irradianceOut)))) return;
  vec4 normalW = texelFetch(levelNormal, texel, 0);
  bool surface = fullResolution ? int(normalW.w) == kPixelSurface : normalW.w > 0.0;
  if (!surface || dot(normalW.xyz, normalW.xyz) <= 0.0) {
    imageStore(irradianceOut, texel, vec4(0.0));
    return;
  }
  vec3 position = texelFetch(levelPositionDepth, texel, 0).xyz;
  vec3 normal = normalize(normalW.xyz);
  vec3 irradiance = vec3(0.0);
  for (int i = 0; i < vplCount; ++i) {
    vec3 towardsLight;
    irradiance += vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                              vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
  }
  imageStore(irradianceOut, texel, vec4(irradiance, 1.0));
}
