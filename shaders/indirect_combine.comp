#version 450 core
#extension GL_GOOGLE_include_directive : require
// Indirect light at full resolution: each surface pixel takes the irradiance gathered at a
// coarser level, the bilinear combination of its four nearest texels weighted by how well their
// position and normal agree with its own (as upsample.comp, the normals more steeply), and
// gathers it exactly where the agreeing texels carry less than kIndirectRefineBelow of the weight
// (edges, thin features).
// Adds albedo/pi times the irradiance to the radiance and writes that term alone to
// indirectImage. The exact pixels gather as gather_indirect.comp does, in the same batches of
// secondary VPLs with shadows: the first dispatch (firstVpl 0) writes every pixel, later ones
// add their batch to the exact pixels only.
#include "shared.h"
#include "shading.glsl"
#include "shadow_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };

layout(binding = 0) uniform sampler2D gPositionDepth;
layout(binding = 1) uniform sampler2D gNormalKind;
layout(binding = 2) uniform sampler2D gAlbedo;
layout(binding = 3) uniform sampler2D levelPositionDepth;
layout(binding = 4) uniform sampler2D levelNormal;
layout(binding = 5) uniform sampler2D levelIrradiance;
layout(rgba32f, binding = 0) uniform image2D radianceImage;
layout(rgba32f, binding = 1) uniform image2D indirectImage;  // w: 1 gathered exactly

#include "secondary_gather.glsl"

uniform int scale;  // full-resolution pixels per level texel along each axis (2^level)
uniform int firstVpl;  // this dispatch's batch of the exact pixels: VPLs firstVpl to endVpl - 1
uniform int endVpl;
// Width of the agreement test, as a fraction of the pixel's distance to the eye.
uniform float planeTolerance;

#include "level_agreement.glsl"

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(radianceImage)))) return;
  vec4 normalKind = texelFetch(gNormalKind, pixel, 0);
  if (int(normalKind.w) != kPixelSurface) {
    if (firstVpl == 0) imageStore(indirectImage, pixel, vec4(0.0));
    return;
  }
  vec3 irradiance;
  float exact = 0.0;
  if (scale == 1) {
    irradiance = texelFetch(levelIrradiance, pixel, 0).rgb;
  } else {
    vec4 positionDepth = texelFetch(gPositionDepth, pixel, 0);
    vec3 normal = normalize(normalKind.xyz);
    ivec2 levelSize = textureSize(levelIrradiance, 0);
    vec2 coarse = (vec2(pixel) + 0.5) / float(scale) - 0.5;
    ivec2 base = ivec2(floor(coarse));
    vec2 fraction = coarse - vec2(base);
    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    float blendWeightSum = 0.0;
    for (int i = 0; i < 4; ++i) {
      ivec2 step = ivec2(i & 1, i >> 1);
      ivec2 tap = clamp(base + step, ivec2(0), levelSize - 1);
      vec4 tapIrradiance = texelFetch(levelIrradiance, tap, 0);
      if (tapIrradiance.w == 0.0) continue;
      vec2 bilinear = mix(1.0 - fraction, fraction, vec2(step));
      vec3 tapNormal = texelFetch(levelNormal, tap, 0).xyz;
      float weight = bilinear.x * bilinear.y *
                     agreement(positionDepth.xyz, normal, positionDepth.w,
                               texelFetch(levelPositionDepth, tap, 0).xyz, tapNormal);
      weightSum += weight;
      // A texel's irradiance was gathered for its own normal, the average over its footprint,
      // which leans halfway to the other face where the footprint straddles an edge: 45 degrees
      // off, agreement() alone still gave such a texel half its weight, and down a box's side
      // face seen at a grazing angle the blend darkened a column of pixels by half
      // (docs/indirect.md, "The upsampling at an edge"). The blend weighs the normals' agreement
      // more steeply; whether to gather exactly stays agreement()'s to decide, since the pixels
      // that a steeper test sent there darkened the bunny's bounce in the mean.
      float facing = max(dot(normal, tapNormal), 0.0);
      float blendWeight = weight * pow(facing, 8.0);
      sum += blendWeight * tapIrradiance.rgb;
      blendWeightSum += blendWeight;
    }
    if (weightSum >= kIndirectRefineBelow) {
      if (firstVpl > 0) return;
      // At least one texel agrees with weight 1/8 or more, so its facing is at least 0.35 and
      // blendWeightSum stays far from zero.
      irradiance = sum / blendWeightSum;
    } else {
      irradiance = secondaryIrradiance(positionDepth.xyz, normal, firstVpl, endVpl, pixel);
      exact = 1.0;
    }
  }
  vec3 indirect = texelFetch(gAlbedo, pixel, 0).rgb / kPi * irradiance;
  imageStore(radianceImage, pixel, imageLoad(radianceImage, pixel) + vec4(indirect, 0.0));
  vec3 earlier = firstVpl > 0 ? imageLoad(indirectImage, pixel).rgb : vec3(0.0);
  imageStore(indirectImage, pixel, vec4(earlier + indirect, exact));
}
