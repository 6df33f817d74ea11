#version 450 core
#extension GL_GOOGLE_include_directive : require
// Level 0 of the discontinuity pyramid, per pixel:
//  r: relative depth gradient |grad z| / z, per pixel, times the image's larger side, so that a
//     plane gives the same value at every resolution;
//  g: normal curvature max |N - N_q| = 2 sin(angle/2) over the 4-neighbourhood, forced to 2
//     where the specular material changes (the gather shares k_s and n across a texel);
//  b: 1 when the pixel is not a lit surface (background or light), which forces refinement of
//     every coarser texel whose footprint holds it;
//  a: light proximity, the pixel's extent on its surface (the distance to its nearer neighbour
//     along each axis, the larger of the two axes) over its distance to the nearest light that
//     can reach it (0 when none can). A light's irradiance bends on the scale of the distance to
//     it, so a texel of 2^l pixels whose extent is a sizeable part of that distance cannot stand
//     for its pixels by interpolation.
// and level 1, pyramid_footprint.glsl's reduction over each 2x2 block of pixels. An invocation
// takes a block of 4x4 pixels: it reads the 32 pixels that their neighbourhoods span once, where
// an invocation per pixel read each pixel five times and the reduction read the pixels again
// (llvmpipe pays for every texel fetch), and one per 2x2 pixels read each three times.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };

#include "light_facing.glsl"

layout(binding = 0) uniform sampler2D gPositionDepth;
layout(binding = 1) uniform sampler2D gNormalKind;
layout(binding = 2) uniform sampler2D gSpecular;
layout(binding = 3) uniform sampler2D gShadowLift;
layout(binding = 4) uniform sampler2D gFaceNormal;
// Level 0's values; level 1's images (pyramid_footprint.glsl) are written when the image has
// more than one level.
layout(rgba32f, binding = 6) uniform writeonly image2D pixelDiscontinuityOut;

#include "pyramid_footprint.glsl"

uniform int lightCount;
uniform bool writesCoarser;

// The block and its border of one: pixel (x, y) of the block, x and y in -1..4, at index
// (y + 1) * 6 + (x + 1); the four corners are not read. A pixel outside the image counts as not
// a surface: a neighbour that is either is skipped.
vec4 positionDepths[36];
vec4 normalKinds[36];
vec4 speculars[36];
bool surfaces[36];

// The discontinuity of the block's pixel at `centre`, from its four neighbours.
vec4 pixelDiscontinuity(int centre, ivec2 size, float lightDistance) {
  if (!surfaces[centre]) return vec4(0.0, 0.0, 1.0, 0.0);
  vec4 normalKind = normalKinds[centre];
  vec4 positionDepth = positionDepths[centre];
  float depth = positionDepth.w;
  const int offsets[4] = int[](1, -1, 6, -6);
  vec2 depthStep = vec2(0.0);
  // Per axis, the distance to the nearer neighbour: across a depth step the other side's.
  vec2 extent = vec2(1e30);
  float curvature = 0.0;
  for (int i = 0; i < 4; ++i) {
    int neighbour = centre + offsets[i];
    if (!surfaces[neighbour]) continue;
    vec4 neighbourPositionDepth = positionDepths[neighbour];
    float difference = abs(neighbourPositionDepth.w - depth);
    float spacing = distance(neighbourPositionDepth.xyz, positionDepth.xyz);
    // The larger of the forward and backward differences, so a step is seen from both sides.
    if (i < 2) {
      depthStep.x = max(depthStep.x, difference);
      extent.x = min(extent.x, spacing);
    } else {
      depthStep.y = max(depthStep.y, difference);
      extent.y = min(extent.y, spacing);
    }
    curvature = max(curvature, length(normalKind.xyz - normalKinds[neighbour].xyz));
    if (speculars[neighbour] != speculars[centre]) curvature = 2.0;
  }
  float gradient = length(depthStep) / max(depth, 1e-6) * float(max(size.x, size.y));
  // An axis without a surface neighbour takes the other's extent (0 when neither has one).
  if (extent.x == 1e30) extent.x = extent.y == 1e30 ? 0.0 : extent.y;
  if (extent.y == 1e30) extent.y = extent.x;
  float proximity = max(extent.x, extent.y) / max(lightDistance, 1e-6);
  return vec4(gradient, curvature, 0.0, proximity);
}

// Reads pixel (x, y) of the block whose first pixel is `origin`.
void loadPixel(ivec2 origin, ivec2 size, int x, int y) {
  int index = (y + 1) * 6 + (x + 1);
  ivec2 pixel = origin + ivec2(x, y);
  surfaces[index] = false;
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, size))) return;
  normalKinds[index] = texelFetch(gNormalKind, pixel, 0);
  surfaces[index] = int(normalKinds[index].w) == kPixelSurface;
  if (!surfaces[index]) return;
  positionDepths[index] = texelFetch(gPositionDepth, pixel, 0);
  speculars[index] = texelFetch(gSpecular, pixel, 0);
}

// The distance from each of the block's pixels to the nearest light that can reach it (1e30 when
// none can), pixel (x, y) at index y * 4 + x. Each light is read once for the sixteen pixels: a
// read of a storage buffer costs llvmpipe more than the tests themselves, and reading the lights
// per pixel took a quarter of the pass on the dragon.
float lightDistances[16];

float nearerReachingLightOfPixel(float nearest, int index, GpuLight light) {
  return surfaces[index] ? nearerReachingLight(nearest, positionDepths[index].xyz,
                                               normalize(normalKinds[index].xyz), light)
                         : nearest;
}

void findLightDistances() {
  for (int i = 0; i < 16; ++i) lightDistances[i] = 1e30;
  for (int l = 0; l < lightCount; ++l) {
    GpuLight light = lights[l];
    lightDistances[0] = nearerReachingLightOfPixel(lightDistances[0], 7, light);
    lightDistances[1] = nearerReachingLightOfPixel(lightDistances[1], 8, light);
    lightDistances[2] = nearerReachingLightOfPixel(lightDistances[2], 9, light);
    lightDistances[3] = nearerReachingLightOfPixel(lightDistances[3], 10, light);
    lightDistances[4] = nearerReachingLightOfPixel(lightDistances[4], 13, light);
    lightDistances[5] = nearerReachingLightOfPixel(lightDistances[5], 14, light);
    lightDistances[6] = nearerReachingLightOfPixel(lightDistances[6], 15, light);
    lightDistances[7] = nearerReachingLightOfPixel(lightDistances[7], 16, light);
    lightDistances[8] = nearerReachingLightOfPixel(lightDistances[8], 19, light);
    lightDistances[9] = nearerReachingLightOfPixel(lightDistances[9], 20, light);
    lightDistances[10] = nearerReachingLightOfPixel(lightDistances[10], 21, light);
    lightDistances[11] = nearerReachingLightOfPixel(lightDistances[11], 22, light);
    lightDistances[12] = nearerReachingLightOfPixel(lightDistances[12], 25, light);
    lightDistances[13] = nearerReachingLightOfPixel(lightDistances[13], 26, light);
    lightDistances[14] = nearerReachingLightOfPixel(lightDistances[14], 27, light);
    lightDistances[15] = nearerReachingLightOfPixel(lightDistances[15], 28, light);
  }
}

// Writes pixel (x, y) of the block's discontinuity and adds the pixel to the block's footprint.
void addPixel(inout Footprint footprint, ivec2 origin, ivec2 size, int x, int y) {
  ivec2 pixel = origin + ivec2(x, y);
  if (any(greaterThanEqual(pixel, size))) return;
  int index = (y + 1) * 6 + (x + 1);
  vec4 discontinuity = pixelDiscontinuity(index, size, lightDistances[y * 4 + x]);
  imageStore(pixelDiscontinuityOut, pixel, discontinuity);
  addChild(footprint, discontinuity);
  if (!surfaces[index]) return;
  addSurface(footprint, 1.0, positionDepths[index], normalKinds[index].xyz, speculars[index]);
  if (shadowRayEnds)
    addShadowRayEnds(footprint, 1.0, texelFetch(gShadowLift, pixel, 0),
                     texelFetch(gFaceNormal, pixel, 0).xyz);
}

// Writes the block's pixels under level 1's texel (x, y) of the block, each 0 or 1, and the
// texel itself when the image has more than one level.
void addCoarserTexel(ivec2 origin, ivec2 size, int x, int y) {
  if (any(greaterThanEqual(origin + 2 * ivec2(x, y), size))) return;
  Footprint footprint = emptyFootprint();
  addPixel(footprint, origin, size, 2 * x, 2 * y);
  addPixel(footprint, origin, size, 2 * x + 1, 2 * y);
  addPixel(footprint, origin, size, 2 * x, 2 * y + 1);
  addPixel(footprint, origin, size, 2 * x + 1, 2 * y + 1);
  if (writesCoarser) storeFootprint(footprint, origin / 2 + ivec2(x, y));
}

void main() {
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(pixelDiscontinuityOut);
  ivec2 origin = 4 * block;
  if (any(greaterThanEqual(origin, size))) return;
  // Each pixel written out, so that every array index is a constant: written as loops, the
  // pass took longer on llvmpipe than the per-pixel pass and the reduction it replaces.
  loadPixel(origin, size, 0, -1);
  loadPixel(origin, size, 1, -1);
  loadPixel(origin, size, 2, -1);
  loadPixel(origin, size, 3, -1);
  loadPixel(origin, size, -1, 0);
  loadPixel(origin, size, 0, 0);
  loadPixel(origin, size, 1, 0);
  loadPixel(origin, size, 2, 0);
  loadPixel(origin, size, 3, 0);
  loadPixel(origin, size, 4, 0);
  loadPixel(origin, size, -1, 1);
  loadPixel(origin, size, 0, 1);
  loadPixel(origin, size, 1, 1);
  loadPixel(origin, size, 2, 1);
  loadPixel(origin, size, 3, 1);
  loadPixel(origin, size, 4, 1);
  loadPixel(origin, size, -1, 2);
  loadPixel(origin, size, 0, 2);
  loadPixel(origin, size, 1, 2);
  loadPixel(origin, size, 2, 2);
  loadPixel(origin, size, 3, 2);
  loadPixel(origin, size, 4, 2);
  loadPixel(origin, size, -1, 3);
  loadPixel(origin, size, 0, 3);
  loadPixel(origin, size, 1, 3);
  loadPixel(origin, size, 2, 3);
  loadPixel(origin, size, 3, 3);
  loadPixel(origin, size, 4, 3);
  loadPixel(origin, size, 0, 4);
  loadPixel(origin, size, 1, 4);
  loadPixel(origin, size, 2, 4);
  loadPixel(origin, size, 3, 4);
  findLightDistances();
  addCoarserTexel(origin, size, 0, 0);
  addCoarserTexel(origin, size, 1, 0);
  addCoarserTexel(origin, size, 0, 1);
  addCoarserTexel(origin, size, 1, 1);
}
