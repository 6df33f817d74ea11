// Whether a texel may take visibility from its parent's mask (visibility_select.comp takes the
// whole mask, or marks the texel's trace-list entry for visibility_trace.comp to take the VPLs on
// which the parent's neighbourhood agrees, and visibility_clear.comp a light the neighbourhood saw
// whole; kTraceTexelParentStands): the parent's surface, averaged over
// its footprint, stands for the texel's own when the averaged normal is within
// kParentNormalAgreement (a cosine) of the texel's and the averaged point lies within
// planeTolerance of the distance to the eye from the texel's tangent plane, the upsampling's test
// of a coarser texel (upsample.comp). A parent that straddles a thin post and the floor at its
// foot averages the two, and its point sees VPLs that the floor texels in the post's narrow
// shadow do not; such a texel traces its own (docs/shadows.md). Include after the declarations
// of levelPositionDepth and levelNormal.
layout(binding = 4) uniform sampler2D parentPositionDepth;
layout(binding = 5) uniform sampler2D parentNormal;
uniform float planeTolerance;

// Whether a surface with point `position` and normal `normal` (not necessarily unit) stands for the
// texel's own by the test above: a parent's averaged surface, or a neighbour's
// (sibling_vpls.glsl).
bool surfaceStandsFor(ivec2 texel, vec3 position, vec3 normal) {
  vec4 own = texelFetch(levelPositionDepth, texel, 0);
  vec3 ownNormal = normalize(texelFetch(levelNormal, texel, 0).xyz);
  return dot(ownNormal, normalize(normal)) >= kParentNormalAgreement &&
         abs(dot(position - own.xyz, ownNormal)) <= planeTolerance * own.w;
}

bool parentStandsFor(ivec2 texel) {
  return surfaceStandsFor(texel, texelFetch(parentPositionDepth, texel / 2, 0).xyz,
                          texelFetch(parentNormal, texel / 2, 0).xyz);
}
