// The irradiance of secondary VPLs first to end - 1 at a receiver, with the bounded form factor
// of the primary VPLs (vplIncident), shared by the indirect gather (gather_indirect.comp) and
// the combine pass's exact pixels (indirect_combine.comp). In the programs compiled for the
// exact hierarchy (--visibility bvh, PENUMBRA_BVH_VISIBILITY) each VPL that can light the
// receiver traces a shadow ray to it: the bounce's second leg. With the voxel grid that leg is
// unshadowed (docs/indirect.md says why), and the switch is the preprocessor's rather than a
// uniform's: with the traversal's code in the shader, even behind a uniform branch, llvmpipe ran
// the unshadowed gather about a third more slowly (the dragon at 1024x1024: 260 to 270 ms
// against 180 to 210).
// Include after shared.h, shading.glsl, shadow_rays.glsl and the VPL buffer.

vec3 secondaryIrradiance(vec3 position, vec3 normal, int first, int end) {
  vec3 irradiance = vec3(0.0);
  vec3 towardsLight;
#ifndef PENUMBRA_BVH_VISIBILITY
  for (int i = first; i < end; ++i)
    irradiance += vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                              vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
#else
  for (int i = first; i < end; ++i) {
    vec3 incident = vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                                vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
    if (incident != vec3(0.0) &&
        vplVisible(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz))
      irradiance += incident;
  }
#endif
  return irradiance;
}
