#version 450 core
#extension GL_GOOGLE_include_directive : require
// The reflective shadow map of one cube face of one light: every texel that sees a surface gets
// the direct light it receives from its own light's VPLs, without visibility (the secondary
// VPLs sampled from the map get theirs: secondary_visibility.comp), and stores the diffuse
// radiance it reflects, its position, its normal (on the light's side) and the area of surface
// the texel covers.
#include "shared.h"
#include "shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };

layout(binding = 0) uniform sampler2D facePositionDepth;
layout(binding = 1) uniform sampler2D faceNormalKind;
layout(binding = 2) uniform sampler2D faceAlbedo;
layout(rgba32f, binding = 0) uniform writeonly image2D positionAreaOut;  // xyz, w area
layout(rgba32f, binding = 1) uniform writeonly image2D normalOut;        // xyz, w 1 when valid
layout(rgba32f, binding = 2) uniform writeonly image2D radianceOut;      // rgb reflected radiance

uniform ivec2 atlasOffset;
uniform vec3 eyePosition;  // the face camera's position, near the light's centre
uniform vec3 faceAxis;     // the face camera's viewing direction
uniform int firstVpl;  // the light's VPLs: firstVpl to endVpl - 1
uniform int endVpl;

// A texel whose surface is seen almost edge-on covers an area that grows without bound; its
// cosine is clamped here. The light such a surface receives from the light's centre falls with
// the same cosine, so the clamp only matters for texels that carry almost no flux.
const float kMinCosine = 0.05;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 faceSize = textureSize(faceNormalKind, 0);
  if (any(greaterThanEqual(texel, faceSize))) return;
  ivec2 target = atlasOffset + texel;
  vec4 normalKind = texelFetch(faceNormalKind, texel, 0);
  vec3 position = texelFetch(facePositionDepth, texel, 0).xyz;
  vec3 offset = position - eyePosition;
  float distanceSquared = dot(offset, offset);
  vec3 direction = offset * inversesqrt(max(distanceSquared, 1e-24));
  float cosAxis = dot(direction, faceAxis);
  if (int(normalKind.w) != kPixelSurface || cosAxis <= 0.0 || distanceSquared <= 0.0) {
    imageStore(positionAreaOut, target, vec4(0.0));
    imageStore(normalOut, target, vec4(0.0));
    imageStore(radianceOut, target, vec4(0.0));
    return;
  }
  vec3 normal = normalize(normalKind.xyz);
  vec3 irradiance = vec3(0.0);
  for (int i = firstVpl; i < endVpl; ++i) {
    vec3 towardsLight;
    irradiance += vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                              vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
  }
  // The texel's solid angle on a 90-degree face, (2/size)^2 cos^3, times r^2 / cos at the surface.
  float texelSide = 2.0 / float(faceSize.x);
  float solidAngle = texelSide * texelSide * cosAxis * cosAxis * cosAxis;
  float cosSurface = max(dot(normal, -direction), kMinCosine);
  float area = solidAngle * distanceSquared / cosSurface;
  vec3 albedo = texelFetch(faceAlbedo, texel, 0).rgb;
  imageStore(positionAreaOut, target, vec4(position, area));
  imageStore(normalOut, target, vec4(normal, 1.0));
  imageStore(radianceOut, target, vec4(albedo / kPi * irradiance, 0.0));
}
