// VPLs shared out among neighbouring texels at the finest level (interleaved sampling, Keller and
// Heidrich 2001, the thesis's proposal). Of the VPLs a texel would trace (every VPL, or those on
// which its parent's neighbourhood disagrees: visibility_trace.comp), it traces only every fourth,
// VPLs 4k + p for its place p in its 2x2 block, and fills in each other quarter from the nearest
// texels of that quarter's place (visibility_share.comp): its two neighbours on either side along
// a row or a column, or its four diagonal neighbours, where their surfaces stand for its own.
// Where they all agree on a VPL, and agree with the texel's own VPLs on either side of it (4k + p
// and the same of the next or the last four, in the light's row), it takes their bit; elsewhere
// it traces the VPL. A straight shadow edge cannot put a texel on another side than both
// neighbours of a pair (or all four diagonal ones), since it lies between them; the test against
// its own VPLs catches shadows narrower than two pixels, such as a VPL row's band on a floor seen
// at a grazing angle. Taking each bit from one neighbour instead shifted the shadow edges by up
// to a pixel (the box scene: 5.4e-4 against reference-vpl at 256x256, where tracing every VPL
// measures 2.5e-5), and taking the pairs' agreement without the own test left the bands (the
// off-screen slab: 9.9e-5 / 0.9944 against 2.1e-5 / 0.9989; docs/shadows.md). A neighbour's bits
// of its own place are final once the trace's rays are done: traced, taken from its parent or
// clear. Include after visibility_texel.glsl and parent_surface.glsl.
layout(r32ui, binding = 2) uniform readonly uimage2D levelFlags;
layout(std430, binding = kGivingNeighbourBinding) buffer GivingNeighbours {
  uint givingNeighbourWords[];
};
// Whether this level shares out its VPLs (the finest level, unless the settings turn it off).
uniform bool shareVplsInBlocks;

// A texel's place in its 2x2 block, 0 to 3.
uint placeInBlock(ivec2 texel) {
  return uint((texel.x & 1) | (texel.y & 1) << 1);
}

// The bits of a mask word that the texels at `place` trace: VPLs 4k + place.
uint vplsOfPlace(uint place) {
  return 0x11111111u << place;
}

// The texels nearest `texel` at `place` (another place than its own): the two on either side
// along the axis on which the places differ, or, where they differ on both, the four diagonal
// neighbours.
int candidateCount(ivec2 texel, uint place) {
  uint differing = placeInBlock(texel) ^ place;
  return differing == 3u ? 4 : 2;
}

ivec2 candidateTexel(ivec2 texel, uint place, int candidate) {
  uint differing = placeInBlock(texel) ^ place;
  int side = (candidate & 1) == 0 ? -1 : 1;
  if (differing == 1u) return texel + ivec2(side, 0);
  if (differing == 2u) return texel + ivec2(0, side);
  return texel + ivec2(side, candidate < 2 ? side : -side);
}

// Whether the texel at `neighbour` may give its VPLs to `texel`: it lies in the image and holds
// a mask, and its surface stands for the texel's by the test by which a parent stands for a
// texel (parent_surface.glsl).
bool neighbourStandsFor(ivec2 texel, ivec2 neighbour) {
  if (any(lessThan(neighbour, ivec2(0))) ||
      any(greaterThanEqual(neighbour, imageSize(levelFlags))) ||
      (imageLoad(levelFlags, neighbour).x & kVisibilityHasMask) == 0u)
    return false;
  return surfaceStandsFor(texel, texelFetch(levelPositionDepth, neighbour, 0).xyz,
                          texelFetch(levelNormal, neighbour, 0).xyz);
}

// The neighbours that give the texel their quarters: bit 4 place + candidate for each candidate
// of each place that stands for it. None where the level does not share out its VPLs.
uint givingNeighbours(ivec2 texel) {
  if (!shareVplsInBlocks) return 0u;
  uint own = placeInBlock(texel);
  uint giving = 0u;
  for (uint place = 0u; place < 4u; ++place) {
    if (place == own) continue;
    for (int candidate = 0; candidate < candidateCount(texel, place); ++candidate)
      if (neighbourStandsFor(texel, candidateTexel(texel, place, candidate)))
        giving |= 1u << (4u * place + uint(candidate));
  }
  return giving;
}

// givingNeighbours for the texel of this invocation's list entry, worked out where `workOut` (the
// trace's first dispatch) and kept for the later steps: each neighbour test reads five textures.
uint givingNeighboursOfEntry(ivec2 texel, bool workOut) {
  if (!shareVplsInBlocks) return 0u;
  uint index = linearInvocationIndex();
  if (!workOut) return givingNeighbourWords[index];
  uint giving = givingNeighbours(texel);
  givingNeighbourWords[index] = giving;
  return giving;
}

// The bits of a mask word that the texel takes from its neighbours instead of tracing: the
// quarters of the places of which a neighbour stands for it (givingNeighbours).
uint givenVpls(uint givingNeighbours) {
  uint bits = 0u;
  for (uint place = 0u; place < 4u; ++place)
    if (((givingNeighbours >> (4u * place)) & 0xfu) != 0u) bits |= vplsOfPlace(place);
  return bits;
}
