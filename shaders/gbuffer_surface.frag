#version 450 core
#extension GL_GOOGLE_include_directive : require
// G-buffer of a lit surface (one draw per material).
#include "shared.h"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 textureUv;

uniform vec3 eyePosition;
uniform vec3 materialAmbient;
uniform vec3 materialDiffuse;
uniform vec3 materialSpecular;
uniform float materialShininess;
uniform bool materialTextured;
layout(binding = 0) uniform sampler2D albedoTexture;

layout(location = 0) out vec4 outPositionDepth;
layout(location = 1) out vec4 outNormalKind;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outEmission;

void main() {
  vec3 towardsEye = eyePosition - worldPosition;
  vec3 normal = normalize(worldNormal);
  // Surfaces are two-sided: seen from behind, they are shaded with the normal facing the eye.
  if (dot(normal, towardsEye) < 0.0) normal = -normal;
  vec3 albedo = materialDiffuse;
  if (materialTextured) albedo *= texture(albedoTexture, textureUv).rgb;
  outPositionDepth = vec4(worldPosition, length(towardsEye));
  outNormalKind = vec4(normal, float(kPixelSurface));
  outAlbedo = vec4(albedo, 1.0);
  outSpecular = vec4(materialSpecular, materialShininess);
  // The light-independent term: the material's ambient on surfaces, the emission on lights.
  outEmission = vec4(materialAmbient, 1.0);
}
