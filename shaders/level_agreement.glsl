// How far a texel of another level stands for a receiver at `position` with unit `normal`, `depth`
// from the eye: 1 on its tangent plane facing the same way, falling with the texel's distance from
// that plane (in planeTolerance times the depth) and with the angle between the normals. The other
// texel's point is `otherPosition` and its normal `otherNormal` (its averaged normal, not of unit
// length). Shared by the upsampling of the gathered levels (upsample.comp, which has read the
// other texels already), the filter over the indirect light's gather level (indirect_filter.comp)
// and its upsampling to full resolution (indirect_combine.comp), which read them through the
// overload below. Include after declaring the `planeTolerance` uniform.
float agreement(vec3 position, vec3 normal, float depth, vec3 otherPosition, vec3 otherNormal) {
  vec3 otherUnitNormal = otherNormal * inversesqrt(max(dot(otherNormal, otherNormal), 1e-24));
  // Distance from the receiver's tangent plane: zero along a plane even when seen at a grazing
  // angle, large across a depth step.
  float offPlane = abs(dot(otherPosition - position, normal)) / (planeTolerance * depth);
  float facing = max(dot(normal, otherUnitNormal), 0.0);
  return facing * facing / (1.0 + offPlane * offPlane);
}

// The same, reading the other texel's point and normal from its level's images.
float agreement(vec3 position, vec3 normal, float depth, sampler2D otherPositionDepth,
                sampler2D otherNormal, ivec2 otherTexel) {
  return agreement(position, normal, depth, texelFetch(otherPositionDepth, otherTexel, 0).xyz,
                   texelFetch(otherNormal, otherTexel, 0).xyz);
}
