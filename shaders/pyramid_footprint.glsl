// A texel of the discontinuity pyramid above level 0, summed over its 2x2 children (fewer at the
// border of sizes that are not powers of two): the maximum of their discontinuity values, and
// the G-buffer averaged over their surfaces, each child weighted by its surface coverage (the
// shadow rays' lift like the position, the face normal like the normal). Both programs that build
// levels use it: discontinuity.comp (level 1) and pyramid_reduce.comp (level 2 and up). The
// level's images are at image units 0 to 5. Include after shared.h.

layout(rgba32f, binding = 0) uniform writeonly image2D positionDepthOut;
// w: the fraction of the footprint covered by lit surface.
layout(rgba32f, binding = 1) uniform writeonly image2D normalOut;
layout(rgba32f, binding = 2) uniform writeonly image2D specularOut;
layout(rgba32f, binding = 3) uniform writeonly image2D discontinuityOut;
layout(rgba32f, binding = 4) uniform writeonly image2D shadowLiftOut;
layout(rgba32f, binding = 5) uniform writeonly image2D faceNormalOut;

// Whether the levels average the shadow rays' ends, which only the visibility passes read: a
// constant in each program (src/render/discontinuity.h), since llvmpipe runs the code of a branch
// that every thread skips, and a uniform made frames without shadows pay for the ends they leave
// out.
#ifdef PENUMBRA_WITHOUT_SHADOW_RAY_ENDS
const bool shadowRayEnds = false;
#else
const bool shadowRayEnds = true;
#endif

struct Footprint {
  vec4 discontinuity;
  vec4 positionDepth;
  vec3 normal;
  vec4 specular;
  vec4 shadowLift;
  vec3 faceNormal;
  float coverage;
  int children;
};

Footprint emptyFootprint() {
  return Footprint(vec4(0.0), vec4(0.0), vec3(0.0), vec4(0.0), vec4(0.0), vec3(0.0), 0.0, 0);
}

// A child inside the finer level, with its discontinuity values.
void addChild(inout Footprint footprint, vec4 discontinuity) {
  ++footprint.children;
  footprint.discontinuity = max(footprint.discontinuity, discontinuity);
}

// A child's surface, `coverage` of it (above 0).
void addSurface(inout Footprint footprint, float coverage, vec4 positionDepth, vec3 normal,
                vec4 specular) {
  footprint.coverage += coverage;
  footprint.positionDepth += coverage * positionDepth;
  footprint.normal += coverage * normal;
  footprint.specular += coverage * specular;
}

// Where a child's shadow rays start, weighted as its surface.
void addShadowRayEnds(inout Footprint footprint, float coverage, vec4 shadowLift,
                      vec3 faceNormal) {
  footprint.shadowLift += coverage * shadowLift;
  footprint.faceNormal += coverage * faceNormal;
}

// Averages the sums and stores the texel; the shadow rays' ends only when `shadowRayEnds`, so
// that a frame without shadows leaves them as they were.
void storeFootprint(Footprint footprint, ivec2 texel) {
  if (footprint.coverage > 0.0) {
    footprint.positionDepth /= footprint.coverage;
    footprint.specular /= footprint.coverage;
    footprint.shadowLift /= footprint.coverage;
    footprint.normal = length(footprint.normal) > 0.0 ? normalize(footprint.normal) : vec3(0.0);
    footprint.faceNormal =
        length(footprint.faceNormal) > 0.0 ? normalize(footprint.faceNormal) : vec3(0.0);
  }
  imageStore(positionDepthOut, texel, footprint.positionDepth);
  imageStore(normalOut, texel,
             vec4(footprint.normal, footprint.coverage / float(max(footprint.children, 1))));
  imageStore(specularOut, texel, footprint.specular);
  imageStore(discontinuityOut, texel, footprint.discontinuity);
  if (shadowRayEnds) {
    imageStore(shadowLiftOut, texel, footprint.shadowLift);
    imageStore(faceNormalOut, texel, vec4(footprint.faceNormal, 0.0));
  }
}
