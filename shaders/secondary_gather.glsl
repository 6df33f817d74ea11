// The irradiance of secondary VPLs first to end - 1 at a receiver, with the bounded form factor
// of the primary VPLs (vplIncident), shared by the indirect gather (gather_indirect.comp) and
// the combine pass's exact pixels (indirect_combine.comp). With `shadowed` (--visibility bvh)
// each VPL that can light the receiver traces a shadow ray to it: the bounce's second leg.
// Otherwise that leg is unshadowed (docs/indirect.md says why the voxel grid does not shadow
// it). Include after shared.h, shading.glsl, shadow_rays.glsl and the VPL buffer.

uniform bool shadowed;

vec3 secondaryIrradiance(vec3 position, vec3 normal, int first, int end) {
  vec3 irradiance = vec3(0.0);
  vec3 towardsLight;
  if (!shadowed) {
    // A loop of its own, as in gather_naive.comp: with the traversal's code in its body
    // llvmpipe runs the loop more slowly even when it traces no ray.
    for (int i = first; i < end; ++i)
      irradiance += vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                                vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
    return irradiance;
  }
  for (int i = first; i < end; ++i) {
    vec3 incident = vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                                vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
    if (incident != vec3(0.0) &&
        vplVisible(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz))
      irradiance += incident;
  }
  return irradiance;
}
