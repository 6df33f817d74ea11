// How far a texel of the indirect light's gather level stands for a receiver at `position` with
// unit `normal`, `depth` from the eye: 1 on its tangent plane facing the same way, falling with
// the texel's distance from that plane (in planeTolerance times the depth) and with the angle
// between the normals. Shared by the filter over the gather level (indirect_filter.comp) and the
// upsampling to full resolution (indirect_combine.comp). Include after declaring the level's
// `levelPositionDepth` and `levelNormal` samplers and the `planeTolerance` uniform.
float agreement(vec3 position, vec3 normal, float depth, ivec2 levelTexel) {
  vec3 otherPosition = texelFetch(levelPositionDepth, levelTexel, 0).xyz;
  vec3 otherNormal = texelFetch(levelNormal, levelTexel, 0).xyz;
  otherNormal *= inversesqrt(max(dot(otherNormal, otherNormal), 1e-24));
  float offPlane = abs(dot(otherPosition - position, normal)) / (planeTolerance * depth);
  float facing = max(dot(normal, otherNormal), 0.0);
  return facing * facing / (1.0 + offPlane * offPlane);
}
