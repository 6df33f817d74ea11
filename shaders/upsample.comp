#version 450 core
#extension GL_GOOGLE_include_directive : require
// Upsampling of one level, from the coarsest to the finest. Computed texels keep what the gather
// wrote; a covered texel takes the bilinear combination of the four nearest texels of the
// coarser level (its parent among them), counting only valid ones, weighted by how well their
// position and normal agree with its own, and renormalised. At level 0 it also writes the final
// radiance: the emission or ambient term, plus albedo/pi times the diffuse sum, plus specular.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(r32ui, binding = 0) uniform readonly uimage2D stateImage;
// This level's results: w = 1 + the level the value came from (negative: unlit), 0 = no value.
layout(rgba32f, binding = 1) uniform image2D diffuseResult;
layout(rgba32f, binding = 2) uniform image2D specularResult;
layout(rgba32f, binding = 3) uniform writeonly image2D radianceOut;

layout(binding = 0) uniform sampler2D levelPositionDepth;
layout(binding = 1) uniform sampler2D levelNormal;
layout(binding = 2) uniform sampler2D coarserPositionDepth;
layout(binding = 3) uniform sampler2D coarserNormal;
layout(binding = 4) uniform sampler2D coarserDiffuse;
layout(binding = 5) uniform sampler2D coarserSpecular;
layout(binding = 6) uniform sampler2D gAlbedo;
layout(binding = 7) uniform sampler2D gEmission;

uniform int level;
uniform bool hasCoarser;
uniform bool writeRadiance;
// Width of the agreement test, as a fraction of the texel's distance to the eye.
uniform float planeTolerance;

#include "level_agreement.glsl"

void upsample(ivec2 texel, out vec4 diffuse, out vec4 specular) {
  ivec2 parent = texel / 2;
  ivec2 step = ivec2(texel.x % 2 == 1 ? 1 : -1, texel.y % 2 == 1 ? 1 : -1);
  ivec2 coarserSize = textureSize(coarserDiffuse, 0);
  vec4 positionDepth = texelFetch(levelPositionDepth, texel, 0);
  vec3 normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  ivec2 taps[4] = ivec2[](parent, parent + ivec2(step.x, 0), parent + ivec2(0, step.y),
                          parent + step);
  const float tent[4] = float[](0.5625, 0.1875, 0.1875, 0.0625);
  // Each tap's light is read once: its w says whether it holds a value (llvmpipe pays for
  // every texel fetch, and this pass runs over every texel of every level).
  vec4 tapDiffuse[4];
  bool valid[4];
  for (int i = 0; i < 4; ++i) {
    bool inside = all(greaterThanEqual(taps[i], ivec2(0))) && all(lessThan(taps[i], coarserSize));
    tapDiffuse[i] = inside ? texelFetch(coarserDiffuse, taps[i], 0) : vec4(0.0);
    valid[i] = tapDiffuse[i].w != 0.0;
  }
  valid[3] = valid[3] && (valid[1] || valid[2]);
  vec3 diffuseSum = vec3(0.0);
  vec3 specularSum = vec3(0.0);
  float weightSum = 0.0;
  vec4 parentSpecular = vec4(0.0);
  for (int i = 0; i < 4; ++i) {
    if (!valid[i]) continue;
    vec4 tapSpecular = texelFetch(coarserSpecular, taps[i], 0);
    if (i == 0) parentSpecular = tapSpecular;
    float weight = tent[i] * agreement(positionDepth.xyz, normal, positionDepth.w,
                                      coarserPositionDepth, coarserNormal, taps[i]);
    diffuseSum += weight * tapDiffuse[i].rgb;
    specularSum += weight * tapSpecular.rgb;
    weightSum += weight;
  }
  if (weightSum > 0.0) {
    diffuse = vec4(diffuseSum / weightSum, tapDiffuse[0].w);
    specular = vec4(specularSum / weightSum, 0.0);
  } else {
    // The parent always covers the texel; when it holds no value (w = 0) neither does the texel.
    diffuse = tapDiffuse[0];
    specular = valid[0] ? parentSpecular : texelFetch(coarserSpecular, parent, 0);
  }
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, imageSize(diffuseResult)))) return;
  uint state = imageLoad(stateImage, texel).x;
  vec4 diffuse = vec4(0.0);
  vec4 specular = vec4(0.0);
  if (state == kTexelComputed) {
    diffuse = imageLoad(diffuseResult, texel);
    specular = imageLoad(specularResult, texel);
  } else if (state == kTexelCovered && hasCoarser) {
    upsample(texel, diffuse, specular);
    imageStore(diffuseResult, texel, diffuse);
    imageStore(specularResult, texel, specular);
  } else {
    // Unlit texels hold a valid zero; refined and invalid ones hold nothing.
    diffuse.w = state == kTexelUnlit ? -float(level + 1) : 0.0;
    imageStore(diffuseResult, texel, diffuse);
    imageStore(specularResult, texel, specular);
  }
  if (writeRadiance) {
    vec3 albedo = texelFetch(gAlbedo, texel, 0).rgb;
    vec3 radiance = texelFetch(gEmission, texel, 0).rgb;
    if (diffuse.w != 0.0) radiance += albedo / kPi * diffuse.rgb + specular.rgb;
    imageStore(radianceOut, texel, vec4(radiance, 1.0));
  }
}
