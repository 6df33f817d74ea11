#version 450 core
#extension GL_GOOGLE_include_directive : require
// The naive renderer: every pixel gathers every VPL at full resolution, with a shadow ray per
// VPL through the voxel grid when shadows are on. With shadows the VPLs come in batches of the
// device profile's shadowRaysPerDispatch, one dispatch each (device_profile.h says why): a batch
// adds its light and its count of visible VPLs to the pixel (rgb and a), and the last batch
// writes the pixel's final radiance.
#include "shared.h"
#include "shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#include "gather_vpls.glsl"

#include "shadow_rays.glsl"

layout(binding = 0) uniform sampler2D gPositionDepth;
layout(binding = 1) uniform sampler2D gNormalKind;
layout(binding = 2) uniform sampler2D gAlbedo;
layout(binding = 3) uniform sampler2D gSpecular;
layout(binding = 4) uniform sampler2D gEmission;
layout(binding = 5) uniform sampler2D gShadowLift;
layout(binding = 6) uniform sampler2D gFaceNormal;
layout(rgba32f, binding = 0) uniform image2D radianceOut;

uniform vec3 eyePosition;
uniform int vplCount;
uniform int firstVpl;  // this dispatch's batch: VPLs firstVpl to endVpl - 1
uniform int endVpl;
uniform bool shadows;
uniform bool visibleFraction;  // the thesis's shortcut, see gather_hierarchical.comp

struct SurfacePoint {
  vec3 position;
  vec3 normal;
  vec3 shadowLift;  // where its shadow rays start (shadow_rays.glsl)
  vec3 faceNormal;
  vec3 albedo;
  vec4 specular;  // colour and exponent
  vec3 towardsEye;
};

// The light VPL i reflects towards the eye from the point, before any shadow test. canLight is
// false when the VPL cannot light the point at all (they do not face each other).
vec3 reflectedFrom(int i, SurfacePoint point, out bool canLight) {
  GpuVpl vpl = vpls[i];
  vec3 towardsLight;
  vec3 incident = vplIncident(point.position, point.normal, vpl.positionArea.xyz, vpl.normal.xyz,
                              vpl.positionArea.w, vpl.radiance.rgb, towardsLight);
  canLight = incident != vec3(0.0);
  return incident * phongBrdf(point.albedo, point.specular.rgb, point.specular.w, point.normal,
                              towardsLight, point.towardsEye);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(radianceOut)))) return;
  vec4 normalKind = texelFetch(gNormalKind, pixel, 0);
  vec3 reflected = vec3(0.0);
  int visibleCount = 0;
  if (firstVpl > 0) {
    vec4 earlier = imageLoad(radianceOut, pixel);
    reflected = earlier.rgb;
    visibleCount = int(earlier.a);
  }
  if (int(normalKind.w) == kPixelSurface) {
    SurfacePoint point;
    point.position = texelFetch(gPositionDepth, pixel, 0).xyz;
    point.normal = normalKind.xyz;
    point.shadowLift = texelFetch(gShadowLift, pixel, 0).xyz;
    point.faceNormal = texelFetch(gFaceNormal, pixel, 0).xyz;
    point.albedo = texelFetch(gAlbedo, pixel, 0).rgb;
    point.specular = texelFetch(gSpecular, pixel, 0);
    point.towardsEye = normalize(eyePosition - point.position);
    bool canLight;
    if (!shadows) {
      // A loop of its own: with the traversal's code in its body, llvmpipe runs the loop over
      // twice as slowly even when it traces no ray (measured on the demo at 512x512).
      for (int i = firstVpl; i < endVpl; ++i) reflected += reflectedFrom(i, point, canLight);
    } else {
      for (int i = firstVpl; i < endVpl; ++i) {
        vec3 light = reflectedFrom(i, point, canLight);
        // Per-pixel visibility: a shadow ray for every VPL that can light the pixel at all.
        bool visible =
            !canLight || surfacePointSeesVpl(point.position, point.shadowLift, point.normal,
                                             point.faceNormal, vpls[i].positionArea.xyz,
                                             vpls[i].normal.xyz);
        if (visible) ++visibleCount;
        if (visible || visibleFraction) reflected += light;
      }
    }
  }
  if (endVpl < vplCount) {
    imageStore(radianceOut, pixel, vec4(reflected, float(visibleCount)));
    return;
  }
  if (shadows && visibleFraction) reflected *= float(visibleCount) / float(vplCount);
  imageStore(radianceOut, pixel, vec4(texelFetch(gEmission, pixel, 0).rgb + reflected, 1.0));
}
