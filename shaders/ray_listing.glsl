// The shadow rays a step of bitmask visibility (visibility_trace.comp, visibility_share.comp)
// leaves to visibility_rays.comp: listed one per entry, (texel's list entry, VPL), and counted
// per level. Include after visibility_texel.glsl and shadow_rays.glsl, with the declarations of
// the `vpls`, `shadowRays`, `rayList` and `rayListDispatch` buffers.
uniform uint rayListCapacity;

// Lists the rays to the VPLs of `toTrace` (bits of mask word `word`) from the texel of this
// invocation's list entry, and returns no bits; where the list is full, traces them here and
// returns the bits of the visible ones (vplBitSet).
uint listOrTraceRays(uint toTrace, int word, TexelSurface surface) {
  if (toTrace == 0u) return 0u;
  uint rays = uint(bitCount(toTrace));
  uint before = atomicAdd(shadowRays[3 * level], rays);
  if (before + rays < before) atomicAdd(shadowRays[3 * level + 1], 1u);
  uint listed = atomicAdd(rayListDispatch.texelCount, rays);
  if (listed + rays <= rayListCapacity) {
    while (toTrace != 0u) {
      int bit = findLSB(toTrace);
      toTrace &= toTrace - 1u;
      rayList[listed++] = uvec2(linearInvocationIndex(), uint(word * 32 + bit));
    }
    return 0u;
  }
  uint bits = 0u;
  while (toTrace != 0u) {
    int bit = findLSB(toTrace);
    toTrace &= toTrace - 1u;
    if (vplBitSet(surface.position, surface.shadowLift, surface.normal, surface.faceNormal,
                  vpls[word * 32 + bit]))
      bits |= 1u << uint(bit);
  }
  return bits;
}
