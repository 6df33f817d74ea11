#version 450 core
#extension GL_GOOGLE_include_directive : require
// Shadows in the reflective shadow maps, paid for only where the secondary VPLs were placed:
// the maps are lit without visibility, the VPLs are sampled from that flux, and each VPL's
// radiance is then scaled, channel by channel, by the fraction of its light's irradiance that
// reaches it past the voxel grid. The estimate stays unbiased (a VPL in shadow carries nothing
// rather than never being placed) at 1/(texels per VPL) of the shadow rays of shadowing every
// texel. One invocation per secondary VPL; its light's VPLs come in batches of
// the device profile's shadowRaysPerDispatch, one dispatch each (device_profile.h says why),
// summed in `sums`.
//
// Interleaved like the gather (secondary_gather.glsl): each secondary VPL estimates its fraction
// from one quarter of its light's VPLs, those whose cells have one parity in each direction of
// the light's grid (a grid of half the side over the whole light), so that four times the
// secondary VPLs cost the rays of one. Successive VPLs of one gather subset take the quarters in
// turn, so a receiver's VPLs see the light through all four.
#include "shared.h"
#include "shading.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = kVplBinding) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = kSecondaryVplBinding) buffer Secondary { GpuVpl secondary[]; };
layout(std430, binding = kSecondarySumsBinding) buffer Sums { vec4 sums[]; };  // 2 per VPL

#include "shadow_rays.glsl"

uniform int secondaryCount;
uniform int vplsPerLight;
uniform int firstVpl;  // this dispatch's VPLs of each light: firstVpl to endVpl - 1
uniform int endVpl;

void main() {
  int k = int(gl_GlobalInvocationID.x);
  if (k >= secondaryCount) return;
  GpuVpl vpl = secondary[k];
  int light = int(vpl.normal.w);
  vec3 position = vpl.positionArea.xyz;
  vec3 normal = vpl.normal.xyz;
  vec3 total = firstVpl == 0 ? vec3(0.0) : sums[2 * k].rgb;
  vec3 visible = firstVpl == 0 ? vec3(0.0) : sums[2 * k + 1].rgb;
  int side = int(round(sqrt(float(vplsPerLight))));
  int quarter = (k / kInterleavedSubsets) % kInterleavedSubsets;
  for (int j = firstVpl; j < endVpl; ++j) {
    if (side >= 2 && (j % side & 1) + 2 * (j / side & 1) != quarter) continue;
    int i = light * vplsPerLight + j;
    vec3 towardsLight;
    vec3 incident = vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                                vpls[i].positionArea.w, vpls[i].radiance.rgb, towardsLight);
    if (incident == vec3(0.0)) continue;
    total += incident;
    if (vplVisible(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz))
      visible += incident;
  }
  if (endVpl < vplsPerLight) {
    sums[2 * k] = vec4(total, 0.0);
    sums[2 * k + 1] = vec4(visible, 0.0);
    return;
  }
  vec3 fraction = vec3(total.r > 0.0 ? visible.r / total.r : 0.0,
                       total.g > 0.0 ? visible.g / total.g : 0.0,
                       total.b > 0.0 ? visible.b / total.b : 0.0);
  secondary[k].radiance = vec4(vpl.radiance.rgb * fraction, 0.0);
}
