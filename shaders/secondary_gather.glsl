// The irradiance of secondary VPLs first to end - 1 at a receiver, shared by the indirect gather
// (gather_indirect.comp) and the combine pass's exact pixels (indirect_combine.comp). The
// bounce's second leg is shadowed in the programs that are given shadow rays: through the exact
// hierarchy (--visibility bvh, PENUMBRA_BVH_VISIBILITY) each VPL that can light the receiver
// traces a shadow ray to it; through the voxel grid, in the gather, one ray stands for a cluster
// of kSecondaryVplsPerShadowRay VPLs that lie close together (gather_indirect.comp), which took
// the default's relative MSE against the reference on the two-light box from 2.0e-3 to 6.1e-4
// (docs/indirect.md). Shadowed, a VPL near the receiver counts as the patch of surface it stands
// for (patchIncident). Unshadowed (no shadows, a screen grid, and the hierarchy's exact pixels
// with the voxel grid) the VPLs keep the bounded form factor of the primary VPLs (vplIncident):
// its loss next to surfaces offsets part of the unshadowed leg's leak. The switch is the
// preprocessor's rather than a uniform's: with the traversal's code in the shader, even behind a
// uniform branch, llvmpipe ran the unshadowed gather about a third more slowly (the dragon at
// 1024x1024: 260 to 270 ms against 180 to 210).
// Include after shared.h, shading.glsl, shadow_rays.glsl and the VPL buffer.
//
// Interleaved sampling (Keller and Heidrich 2001): where the gather runs at a coarser level, the
// receivers of each 2x2 block of texels (and the pixels gathered exactly, by their own parity) take
// one subset each of the secondary VPLs, every kInterleavedSubsets-th, each VPL standing for
// that many times its area. Each subset is a stratified sample of the flux on its own, so every
// receiver's estimate stays unbiased, and neighbouring receivers' errors are independent: a
// filter over the gather level (indirect_filter.comp) averages the four subsets, where with one
// set for all the same VPLs' blotches showed in every texel. Four times the VPLs at the cost per
// receiver of one subset took the bounce's relative MSE against the reference from 1.05e-3 to
// 4.5e-4 on the two-light box (docs/indirect.md).
uniform int secondaryVplCount;  // all the secondary VPLs, of every subset
uniform bool interleaved;      // whether a receiver takes only its subset of them

// One edge's term of Lambert's irradiance from a uniformly emitting polygon, the edge from a to
// b (directions from the receiver): the angle it subtends times its plane's normal . n.
float lambertEdge(vec3 a, vec3 b, vec3 normal) {
  a = normalize(a);
  b = normalize(b);
  vec3 edgePlane = cross(a, b);
  float sine = length(edgePlane);
  return sine > 1e-7 ? atan(sine, dot(a, b)) * dot(edgePlane, normal) / sine : 0.0;
}

// A secondary VPL closer than this many times the side of its patch is integrated over the
// patch; farther away the bounded form factor stands for it (on the square's axis at 4 sides
// the two differ by under 0.1%).
const float kPatchNearFieldSides = 4.0;

// Whether a receiver `offset` from a patch's centre takes the patch's integral: in its near field
// and in front of it (behind it, the bounded form factor is zero as well).
bool inNearField(vec3 offset, vec3 vplNormal, float vplArea) {
  return dot(offset, offset) <= kPatchNearFieldSides * kPatchNearFieldSides * vplArea &&
         dot(vplNormal, offset) < 0.0;
}

// The irradiance, per unit radiance, at a receiver `offset` from a patch's centre within the
// near field: Lambert's exact polygon integral over the patch, a square of `vplArea` in the
// plane of `vplNormal`, clipped to the receiver's hemisphere (patchIncident says why).
float nearPatchIrradiance(vec3 offset, vec3 normal, vec3 vplNormal, float vplArea) {
  // Any basis of the tangent plane will do: the squares' orientations average out.
  vec3 helper = abs(vplNormal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 tangent = 0.5 * sqrt(vplArea) * normalize(cross(helper, vplNormal));
  vec3 bitangent = cross(vplNormal, tangent);
  // The square's edges clipped to the receiver's hemisphere (Sutherland-Hodgman, kept as running
  // sums: with the clipped polygon in an array, which llvmpipe spilled, the gather took 2120 ms
  // on the dragon at 1024x1024 against 1333 ms like this, unshadowed). A convex
  // polygon cut by a plane leaves it once and comes back once; the part of the plane between
  // those two points closes the clipped polygon.
  float sum = 0.0;
  vec3 doubledArea = vec3(0.0);  // the clipped polygon's vector area, times two
  vec3 leaves = vec3(0.0);
  vec3 enters = vec3(0.0);
  bool clipped = false;
  vec3 a = offset - tangent - bitangent;
  for (int i = 0; i < 4; ++i) {
    vec3 b = offset + (i == 0 ? tangent - bitangent
                              : i == 1 ? tangent + bitangent
                                       : i == 2 ? -tangent + bitangent : -tangent - bitangent);
    float heightA = dot(a, normal);
    float heightB = dot(b, normal);
    if (heightA >= 0.0 && heightB >= 0.0) {
      sum += lambertEdge(a, b, normal);
      doubledArea += cross(a, b);
    } else if (heightA >= 0.0 || heightB >= 0.0) {
      vec3 crossing = a + (b - a) * (heightA / (heightA - heightB));
      clipped = true;
      if (heightA >= 0.0) {
        sum += lambertEdge(a, crossing, normal);
        doubledArea += cross(a, crossing);
        leaves = crossing;
      } else {
        sum += lambertEdge(crossing, b, normal);
        doubledArea += cross(crossing, b);
        enters = crossing;
      }
    }
    a = b;
  }
  if (!clipped) return 0.5 * abs(sum);
  sum += lambertEdge(leaves, enters, normal);
  doubledArea += cross(leaves, enters);
  // A patch whose centre lies above the receiver's plane keeps its whole flux on the part above
  // it. What the plane cuts off is either not there (the patch's surface ends at the receiver's,
  // a wall at a floor) or stood for by patches whose centres lie below, which this receiver
  // never sees (their rays go through its own surface); either way, with the cut part dropped,
  // surfaces next to the plane came out dark on average by an amount that grows with the patch
  // (docs/indirect.md). A centrally symmetric square keeps at least half its area on its
  // centre's side, so the scale is at most 2.
  float clippedArea = 0.5 * length(doubledArea);
  float scale = dot(offset, normal) > 0.0 && clippedArea > 0.0 ? vplArea / clippedArea : 1.0;
  return 0.5 * abs(sum) * scale;
}

// Irradiance at a receiver from a secondary VPL taken as what it stands for: a uniformly
// emitting patch of its area on its surface, a square in its tangent plane. The bounded form
// factor of the primary VPLs (vplIncident) keeps the cosines of the patch's centre for all of
// it, so next to a VPL's surface (a floor along a wall) its light falls towards zero where the
// patch fills half the sky, and the bounce came out 6 to 15% dark with 256 VPLs (docs/
// indirect.md). Near the patch the irradiance is Lambert's exact polygon integral over the
// square clipped to the receiver's hemisphere; summed over VPLs placed with density 1/area the
// squares' integrals average out to the surfaces' own, where the bounded form does not.
vec3 patchIncident(vec3 position, vec3 normal, vec3 vplPosition, vec3 vplNormal, float vplArea,
                   vec3 vplRadiance) {
  vec3 offset = vplPosition - position;
  if (inNearField(offset, vplNormal, vplArea))
    return vplRadiance * nearPatchIrradiance(offset, normal, vplNormal, vplArea);
  vec3 towardsLight;
  return vplIncident(position, normal, vplPosition, vplNormal, vplArea, vplRadiance, towardsLight);
}

// A receiver's share of the secondary VPLs first to end - 1: every stride-th from start, each
// standing for areaScale times its own area.
struct VplSubset {
  int start;
  int stride;
  float areaScale;
};

// `cell` is the receiver's texel (or pixel), whose parity picks the subset when interleaved.
VplSubset subsetOf(int first, ivec2 cell) {
  if (!interleaved) return VplSubset(first, 1, 1.0);
  int subset = (cell.x & 1) + 2 * (cell.y & 1);
  int stride = kInterleavedSubsets;
  // With a count that is not a multiple of the stride the subsets differ by one VPL; each
  // stands for the whole flux, so a VPL of a subset of n stands for count / n of its own share.
  int subsetSize = (secondaryVplCount - subset + stride - 1) / stride;
  return VplSubset(first + (subset - first % stride + stride) % stride, stride,
                   float(secondaryVplCount) / float(max(subsetSize, 1)));
}

// The irradiance at a receiver of the secondary VPLs first to end - 1 that belong to its subset,
// unshadowed or, in the BVH's programs, each shadowed (the voxel programs shadow clusters of them
// instead: gather_indirect.comp).
vec3 secondaryIrradiance(vec3 position, vec3 normal, int first, int end, ivec2 cell) {
  VplSubset subset = subsetOf(first, cell);
  vec3 irradiance = vec3(0.0);
#if defined(PENUMBRA_BVH_VISIBILITY)
  for (int i = subset.start; i < end; i += subset.stride) {
    vec3 incident =
        patchIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                      subset.areaScale * vpls[i].positionArea.w, vpls[i].radiance.rgb);
    if (incident != vec3(0.0) &&
        vplVisible(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz))
      irradiance += incident;
  }
#else
  vec3 towardsLight;
  for (int i = subset.start; i < end; i += subset.stride)
    irradiance += vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                              subset.areaScale * vpls[i].positionArea.w, vpls[i].radiance.rgb,
                              towardsLight);
#endif
  return irradiance;
}

// Through the voxel grid one shadow ray stands for a cluster of kSecondaryVplsPerShadowRay
// consecutive VPLs of a subset, which lie close together in the VPLs' cluster order. Cluster k of
// a subset starts at start + k * stride * kSecondaryVplsPerShadowRay; a batch's first VPL is a
// multiple of that stride (IndirectGatherPass), so that every batch cuts the subsets into the
// same clusters.
int clusterCount(VplSubset subset, int end) {
  int clusterStride = subset.stride * kSecondaryVplsPerShadowRay;
  return max(end - subset.start + clusterStride - 1, 0) / clusterStride;
}

// The light of cluster k at a receiver, unshadowed: each VPL as the patch it stands for
// (patchIncident). The near field's integrals come after the far field's sum, in a loop over the
// VPLs that need them: llvmpipe runs an if's body for every thread whether any takes it or not,
// but skips a loop that no thread enters, and with the integral inside the sum's loop the
// gather's program without its rays took 185 to 200 ms on the dragon at 1024x1024 against 140 to
// 170 ms like this.
vec3 clusterIncident(vec3 position, vec3 normal, VplSubset subset, int end, int k) {
  int cluster = subset.start + k * subset.stride * kSecondaryVplsPerShadowRay;
  int clusterEnd = min(cluster + subset.stride * kSecondaryVplsPerShadowRay, end);
  vec3 incident = vec3(0.0);
  uint near = 0u;
  for (int i = cluster, bit = 0; i < clusterEnd; i += subset.stride, ++bit) {
    vec3 offset = vpls[i].positionArea.xyz - position;
    float area = subset.areaScale * vpls[i].positionArea.w;
    if (inNearField(offset, vpls[i].normal.xyz, area)) {
      near |= 1u << bit;
    } else {
      vec3 towardsLight;
      incident += vplIncident(position, normal, vpls[i].positionArea.xyz, vpls[i].normal.xyz,
                              area, vpls[i].radiance.rgb, towardsLight);
    }
  }
  while (near != 0u) {
    int i = cluster + findLSB(near) * subset.stride;
    near &= near - 1u;
    incident += vpls[i].radiance.rgb *
                nearPatchIrradiance(vpls[i].positionArea.xyz - position, normal,
                                    vpls[i].normal.xyz, subset.areaScale * vpls[i].positionArea.w);
  }
  return incident;
}

// Whether cluster k is visible from a receiver: one ray to its middle VPL, the nearest to the
// others (against its first: relative MSE 5.8e-4 against 6.8e-4 on the two-light box,
// docs/indirect.md).
bool clusterVisible(vec3 position, vec3 normal, VplSubset subset, int end, int k) {
  int cluster = subset.start + k * subset.stride * kSecondaryVplsPerShadowRay;
  int middle = cluster + min(kSecondaryVplsPerShadowRay / 2, (end - 1 - cluster) / subset.stride) *
                             subset.stride;
  return vplVisible(position, normal, vpls[middle].positionArea.xyz, vpls[middle].normal.xyz);
}
