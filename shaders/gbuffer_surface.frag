#version 450 core
#extension GL_GOOGLE_include_directive : require
// G-buffer of a lit surface (one draw per material). For the reflective shadow map's faces and for
// frames without shadows it is compiled with PENUMBRA_WITHOUT_SHADOW_RAY_STARTS: nothing reads the
// shadow-ray starts (lift, face normal, mesh) there, which stay zero, and it never reads
// gl_PrimitiveID, whose use alone made llvmpipe draw the dragon's five faces nearly twice as
// slowly (src/render/gbuffer.h).
#include "shared.h"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 textureUv;

// The surface vertex and index buffers the draw reads (SceneGpu), for the corners of the
// fragment's triangle: its draw's first triangle plus gl_PrimitiveID (without a geometry shader,
// the primitives drawn before it in the draw). The corners are read, not passed down by a
// geometry shader, since one changes llvmpipe's interpolation of the other inputs by a unit in
// the last place, and with it every image.
layout(std430, binding = kGeometryVertexBinding) readonly buffer Vertices { float vertexData[]; };
layout(std430, binding = kGeometryIndexBinding) readonly buffer Indices { uint indices[]; };
layout(std430, binding = kGeometryMeshBinding) readonly buffer MeshFirstVertices {
  uint meshFirstVertices[];
};
uniform uint firstTriangle;
uniform int meshCount;  // meshFirstVertices' entries (its store may be longer)

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
layout(location = 5) out vec4 outShadowLift;
layout(location = 6) out vec4 outFaceNormal;

vec3 vertexVector(uint vertex, uint component) {
  uint base = vertex * uint(kFloatsPerVertex) + component;
  return vec3(vertexData[base], vertexData[base + 1u], vertexData[base + 2u]);
}

// The index of the mesh (a part of an object with one material) a vertex belongs to: the last
// whose first vertex is not past it.
uint meshOfVertex(uint vertex) {
  int low = 0;
  int high = meshCount - 1;
  while (low < high) {
    int middle = (low + high + 1) / 2;
    if (meshFirstVertices[middle] <= vertex)
      low = middle;
    else
      high = middle - 1;
  }
  return uint(low);
}

// Barycentric weights of a point of the triangle's plane.
vec3 barycentricWeights(vec3 position, vec3 corners[3]) {
  vec3 u = corners[1] - corners[0];
  vec3 v = corners[2] - corners[0];
  vec3 w = position - corners[0];
  float uu = dot(u, u);
  float uv = dot(u, v);
  float vv = dot(v, v);
  float denominator = uu * vv - uv * uv;
  float weight1 = (vv * dot(w, u) - uv * dot(w, v)) / denominator;
  float weight2 = (uu * dot(w, v) - uv * dot(w, u)) / denominator;
  return vec3(1.0 - weight1 - weight2, weight1, weight2);
}

// The port of liftedOntoNormals (src/scene/shadow_terminator.h, which says what it does; the
// tests compare the two): the point shadow rays start from, on the curved surface the corners'
// normals describe. `side` is -1 where the surface is seen from behind its normals.
vec3 liftedOntoNormals(vec3 position, vec3 corners[3], vec3 cornerNormals[3], vec3 weights,
                       float side) {
  vec3 lifted = position;
  for (int corner = 0; corner < 3; ++corner) {
    vec3 normal = cornerNormals[corner];
    float normalLength = length(normal);
    if (!(normalLength > 0.0)) continue;
    vec3 unit = side * normal / normalLength;
    float height = dot(position - corners[corner], unit);
    lifted -= weights[corner] * min(0.0, height) * unit;
  }
  return lifted;
}

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
#ifdef PENUMBRA_WITHOUT_SHADOW_RAY_STARTS
  vec3 faceNormal = vec3(0.0);
#else
  uint triangle = firstTriangle + uint(gl_PrimitiveID);
  vec3 corners[3];
  vec3 cornerNormals[3];
  for (uint corner = 0u; corner < 3u; ++corner) {
    uint vertex = indices[3u * triangle + corner];
    corners[corner] = vertexVector(vertex, 0u);
    cornerNormals[corner] = vertexVector(vertex, 3u);
  }
  // The triangle's own plane, facing the eye, as the reference takes it: shadow rays leave the
  // surface along it (shadow_rays.glsl), since a smooth normal can lean through the face.
  vec3 faceNormal = cross(corners[1] - corners[0], corners[2] - corners[0]);
  if (dot(faceNormal, towardsEye) < 0.0) faceNormal = -faceNormal;
  faceNormal = normalize(faceNormal);
#endif
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
    outShadowLift = vec4(0.0);
    outFaceNormal = vec4(faceNormal, 0.0);
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
#ifdef PENUMBRA_WITHOUT_SHADOW_RAY_STARTS
  outShadowLift = vec4(0.0);
  outFaceNormal = vec4(0.0);
#else
  vec3 lifted = liftedOntoNormals(worldPosition, corners, cornerNormals,
                                 barycentricWeights(worldPosition, corners),
                                 frontSide ? 1.0 : -1.0);
  outShadowLift = vec4(lifted - worldPosition, 0.0);
  outFaceNormal = vec4(faceNormal, float(meshOfVertex(indices[3u * triangle]) + 1u));
#endif
}
