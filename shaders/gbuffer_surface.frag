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
// A mesh light's material (docs/mesh-lights.md): white 1x1 texture when it has none.
uniform bool materialEmits;
uniform vec3 materialEmission;
uniform bool materialTwoSided;
layout(binding = 0) uniform sampler2D albedoTexture;
layout(binding = 1) uniform sampler2D emissionTexture;

layout(location = 0) out vec4 outPositionDepth;
layout(location = 1) out vec4 outNormalKind;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outEmission;

void main() {
  vec3 towardsEye = eyePosition - worldPosition;
  vec3 normal = normalize(worldNormal);
  // Surfaces are two-sided (docs/scene-format.md): seen from behind, the eye on the other side
  // of the face from where the normal points, they are shaded with the normal flipped. The face
  // decides, not the angle to the eye, as in the reference: a smooth normal that leans away from
  // a grazing eye on the front side is kept. The face's plane comes from the position's screen
  // derivatives (one triangle's plane within a 2x2 quad); where they vanish, the eye decides.
  vec3 face = cross(dFdx(worldPosition), dFdy(worldPosition));
  if (dot(face, face) == 0.0) face = towardsEye;
  if (dot(face, towardsEye) < 0.0) face = -face;
  bool frontSide = dot(normal, face) >= 0.0;
  if (!frontSide) normal = -normal;
  if (materialEmits) {
    // Like a light quad: its emission on the emitting side, black behind, and never lit.
    vec3 radiance = vec3(0.0);
    if (frontSide || materialTwoSided)
      radiance = materialEmission * texture(emissionTexture, textureUv).rgb;
    outPositionDepth = vec4(worldPosition, length(towardsEye));
    outNormalKind = vec4(normal, float(kPixelEmitter));
    outAlbedo = vec4(0.0);
    outSpecular = vec4(0.0);
    outEmission = vec4(radiance, 1.0);
    return;
  }
  vec3 albedo = materialDiffuse;
  if (materialTextured) albedo *= texture(albedoTexture, textureUv).rgb;
  outPositionDepth = vec4(worldPosition, length(towardsEye));
  outNormalKind = vec4(normal, float(kPixelSurface));
  outAlbedo = vec4(albedo, 1.0);
  outSpecular = vec4(materialSpecular, materialShininess);
  // The light-independent term: the material's ambient on surfaces, the emission on lights.
  outEmission = vec4(materialAmbient, 1.0);
}
