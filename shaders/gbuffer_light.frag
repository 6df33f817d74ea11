#version 450 core
#extension GL_GOOGLE_include_directive : require
// G-buffer of a light quad: it shows its emission from the front and is black from behind.
#include "shared.h"
#include "quad_light.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 textureUv;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };

uniform vec3 eyePosition;
uniform int lightIndex;
layout(binding = 0) uniform sampler2D emissionTexture;

layout(location = 0) out vec4 outPositionDepth;
layout(location = 1) out vec4 outNormalKind;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outEmission;
layout(location = 5) out vec4 outShadowLift;
layout(location = 6) out vec4 outFaceNormal;

void main() {
  GpuLight light = lights[lightIndex];
  vec3 towardsEye = eyePosition - worldPosition;
  vec3 radiance = vec3(0.0);
  if (dot(light.normalArea.xyz, towardsEye) > 0.0) {
    radiance = light.emission.rgb;
    if (light.vplInfo.z != 0) {
      vec2 uv = quadUvAt(light.corners[0].xyz, light.corners[1].xyz, light.corners[2].xyz,
                         light.corners[3].xyz, light.normalArea.xyz, worldPosition);
      radiance *= texture(emissionTexture, uv).rgb;
    }
  }
  outPositionDepth = vec4(worldPosition, length(towardsEye));
  outNormalKind = vec4(light.normalArea.xyz, float(kPixelEmitter));
  outAlbedo = vec4(0.0);
  outSpecular = vec4(0.0);
  outEmission = vec4(radiance, 1.0);
  // Lights trace no shadow rays.
  outShadowLift = vec4(0.0);
  outFaceNormal = vec4(light.normalArea.xyz, 0.0);
}
