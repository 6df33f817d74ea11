#version 450 core
#extension GL_GOOGLE_include_directive : require
// Upsampling of one level, from the coarsest to the finest. Computed texels keep what the gather
// wrote; a covered texel takes the bilinear combination of the four nearest texels of the
// coarser level (its parent among them), counting only valid ones, weighted by how well their
// position and normal agree with its own, and renormalised. An invocation takes the 2x2 texels
// under one parent, which share the coarser texels they read.
//
// Built with PENUMBRA_WRITES_RADIANCE, for level 0, it writes the final radiance instead of the
// level's results: the emission or ambient term, plus albedo/pi times the diffuse sum, plus
// specular. Nothing in a frame reads level 0's results, and llvmpipe pays for every store, masked
// or not: only the debug views that show them have them stored, by the program without it.
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
// Width of the agreement test, as a fraction of the texel's distance to the eye.
uniform float planeTolerance;

#include "level_agreement.glsl"

// The coarser level's texels around the block's four parents (the 2x2 coarser texels over its 4x4
// texels), read once for all sixteen texels: offset (x, y) from the first parent, each in -1..2,
// at index (y + 1) * 4 + (x + 1). Each texel takes four of them; an invocation per texel read each
// of them for every texel it covers (llvmpipe pays for every texel fetch, and this pass runs over
// every texel of every level), one per 2x2 texels 2.25 times.
vec4 tapDiffuse[16];
vec4 tapSpecular[16];
vec3 tapPosition[16];
vec3 tapNormal[16];
bool tapValid[16];

void loadTap(ivec2 firstParent, ivec2 coarserSize, int x, int y) {
  int index = (y + 1) * 4 + (x + 1);
  ivec2 tap = firstParent + ivec2(x, y);
  bool inside = all(greaterThanEqual(tap, ivec2(0))) && all(lessThan(tap, coarserSize));
  tapDiffuse[index] = inside ? texelFetch(coarserDiffuse, tap, 0) : vec4(0.0);
  tapValid[index] = tapDiffuse[index].w != 0.0;
  // A parent's specular light stands for a texel none of whose taps agree with it.
  bool isParent = x >= 0 && x <= 1 && y >= 0 && y <= 1;
  if (!tapValid[index] && !isParent) return;
  tapSpecular[index] = texelFetch(coarserSpecular, tap, 0);
  tapPosition[index] = texelFetch(coarserPositionDepth, tap, 0).xyz;
  tapNormal[index] = texelFetch(coarserNormal, tap, 0).xyz;
}

// Texel (x, y) of the block, each in 0..3, from its four nearest coarser texels: its parent, the
// parent's neighbours towards the texel along x and along y, and the one diagonally between them.
void upsample(ivec2 texel, int x, int y, out vec4 diffuse, out vec4 specular) {
  int parent = (y / 2 + 1) * 4 + (x / 2 + 1);
  ivec2 step = ivec2(x % 2 == 1 ? 1 : -1, y % 2 == 1 ? 1 : -1);
  int taps[4] = int[](parent, parent + step.x, parent + 4 * step.y, parent + step.x + 4 * step.y);
  vec4 positionDepth = texelFetch(levelPositionDepth, texel, 0);
  vec3 normal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  const float tent[4] = float[](0.5625, 0.1875, 0.1875, 0.0625);
  bool valid[4];
  for (int i = 0; i < 4; ++i) valid[i] = tapValid[taps[i]];
  valid[3] = valid[3] && (valid[1] || valid[2]);
  vec3 diffuseSum = vec3(0.0);
  vec3 specularSum = vec3(0.0);
  float weightSum = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (!valid[i]) continue;
    float weight = tent[i] * agreement(positionDepth.xyz, normal, positionDepth.w,
                                      tapPosition[taps[i]], tapNormal[taps[i]]);
    diffuseSum += weight * tapDiffuse[taps[i]].rgb;
    specularSum += weight * tapSpecular[taps[i]].rgb;
    weightSum += weight;
  }
  if (weightSum > 0.0) {
    diffuse = vec4(diffuseSum / weightSum, tapDiffuse[parent].w);
    specular = vec4(specularSum / weightSum, 0.0);
  } else {
    // The parent always covers the texel; when it holds no value (w = 0) neither does the texel.
    diffuse = tapDiffuse[parent];
    specular = tapSpecular[parent];
  }
}

// Texel (x, y) of the block whose first texel is `origin`.
void resolveTexel(ivec2 origin, int x, int y) {
  ivec2 texel = origin + ivec2(x, y);
  if (any(greaterThanEqual(texel, imageSize(diffuseResult)))) return;
  uint state = imageLoad(stateImage, texel).x;
  vec4 diffuse = vec4(0.0);
  vec4 specular = vec4(0.0);
  if (state == kTexelCovered && hasCoarser) {
    upsample(texel, x, y, diffuse, specular);
  } else {
    // Unlit texels hold a valid zero; refined and invalid ones hold nothing.
    diffuse.w = state == kTexelUnlit ? -float(level + 1) : 0.0;
  }
#ifdef PENUMBRA_WRITES_RADIANCE
  if (state == kTexelComputed) {
    diffuse = imageLoad(diffuseResult, texel);
    specular = imageLoad(specularResult, texel);
  }
  vec3 albedo = texelFetch(gAlbedo, texel, 0).rgb;
  vec3 radiance = texelFetch(gEmission, texel, 0).rgb;
  if (diffuse.w != 0.0) radiance += albedo / kPi * diffuse.rgb + specular.rgb;
  imageStore(radianceOut, texel, vec4(radiance, 1.0));
#else
  if (state != kTexelComputed) {
    imageStore(diffuseResult, texel, diffuse);
    imageStore(specularResult, texel, specular);
  }
#endif
}

void main() {
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  ivec2 origin = 4 * block;
  if (any(greaterThanEqual(origin, imageSize(diffuseResult)))) return;
  if (hasCoarser) {
    ivec2 coarserSize = textureSize(coarserDiffuse, 0);
    // Each tap and texel written out, so that every array index is a constant (as in
    // discontinuity.comp).
    ivec2 firstParent = 2 * block;
    loadTap(firstParent, coarserSize, -1, -1);
    loadTap(firstParent, coarserSize, 0, -1);
    loadTap(firstParent, coarserSize, 1, -1);
    loadTap(firstParent, coarserSize, 2, -1);
    loadTap(firstParent, coarserSize, -1, 0);
    loadTap(firstParent, coarserSize, 0, 0);
    loadTap(firstParent, coarserSize, 1, 0);
    loadTap(firstParent, coarserSize, 2, 0);
    loadTap(firstParent, coarserSize, -1, 1);
    loadTap(firstParent, coarserSize, 0, 1);
    loadTap(firstParent, coarserSize, 1, 1);
    loadTap(firstParent, coarserSize, 2, 1);
    loadTap(firstParent, coarserSize, -1, 2);
    loadTap(firstParent, coarserSize, 0, 2);
    loadTap(firstParent, coarserSize, 1, 2);
    loadTap(firstParent, coarserSize, 2, 2);
  }
  resolveTexel(origin, 0, 0);
  resolveTexel(origin, 1, 0);
  resolveTexel(origin, 2, 0);
  resolveTexel(origin, 3, 0);
  resolveTexel(origin, 0, 1);
  resolveTexel(origin, 1, 1);
  resolveTexel(origin, 2, 1);
  resolveTexel(origin, 3, 1);
  resolveTexel(origin, 0, 2);
  resolveTexel(origin, 1, 2);
  resolveTexel(origin, 2, 2);
  resolveTexel(origin, 3, 2);
  resolveTexel(origin, 0, 3);
  resolveTexel(origin, 1, 3);
  resolveTexel(origin, 2, 3);
  resolveTexel(origin, 3, 3);
}
