// The pyramid of a clear-light test: the convex hull of a shadow ray's start (the apex) and the
// four corners of the quad its rays may end on. Every VPL is a convex combination of the light's
// corners, so every shadow ray from the apex to one of its VPLs lies inside; when no occluder
// meets the pyramid, every VPL of the light is visible. The voxel grid (voxel_grid.glsl) tests
// the boxes of its occupied cells against it, the BVH (bvh.glsl) its nodes' boxes and triangles.
// The tests only separate (a bounding box, or one of the five faces' planes): not testing the
// axes made of edge pairs only makes them more cautious.

struct LightPyramid {
  vec3 low;  // bounding box
  vec3 high;
  vec4 faces[5];  // xyz outward normal, w the corners' largest projection on it
};

// The plane through a, b and c, turned away from `inside`, offset to bound all five corners, so
// that the test stays on the safe side for any quad, planar or not.
vec4 pyramidFace(vec3 a, vec3 b, vec3 c, vec3 inside, vec3 corners[5]) {
  vec3 normal = cross(b - a, c - a);
  if (dot(normal, inside - a) > 0.0) normal = -normal;
  float offset = dot(normal, corners[0]);
  for (int i = 1; i < 5; ++i) offset = max(offset, dot(normal, corners[i]));
  return vec4(normal, offset);
}

// corners[0] is the apex, corners[1] to corners[4] the quad's corners in order around it.
LightPyramid lightPyramid(vec3 corners[5]) {
  vec3 inside = (corners[0] + corners[1] + corners[2] + corners[3] + corners[4]) / 5.0;
  LightPyramid pyramid;
  pyramid.low = corners[0];
  pyramid.high = corners[0];
  for (int i = 1; i < 5; ++i) {
    pyramid.low = min(pyramid.low, corners[i]);
    pyramid.high = max(pyramid.high, corners[i]);
  }
  for (int i = 0; i < 4; ++i)
    pyramid.faces[i] = pyramidFace(corners[0], corners[i + 1], corners[(i + 1) % 4 + 1], inside,
                                   corners);
  pyramid.faces[4] = pyramidFace(corners[1], corners[2], corners[3], inside, corners);
  return pyramid;
}

bool facePasses(vec4 face, vec3 centre, vec3 halfSize) {
  return dot(face.xyz, centre) - dot(abs(face.xyz), halfSize) <= face.w;
}

// Whether the box may meet the pyramid: false when the pyramid's bounding box or one of its
// faces' planes separates them. The five faces are written out rather than looped over, since
// each loop iteration counts towards llvmpipe's limit.
bool pyramidMeetsBox(LightPyramid pyramid, vec3 low, vec3 high) {
  if (any(greaterThan(low, pyramid.high)) || any(lessThan(high, pyramid.low))) return false;
  vec3 centre = 0.5 * (low + high);
  vec3 halfSize = 0.5 * (high - low);
  return facePasses(pyramid.faces[0], centre, halfSize) &&
         facePasses(pyramid.faces[1], centre, halfSize) &&
         facePasses(pyramid.faces[2], centre, halfSize) &&
         facePasses(pyramid.faces[3], centre, halfSize) &&
         facePasses(pyramid.faces[4], centre, halfSize);
}
