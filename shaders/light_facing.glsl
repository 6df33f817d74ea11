// Needs the `lights` buffer declared before the include.
// Whether a light can reach a point: the point must lie in front of a quad light's plane, and at
// least one corner of the light (of a mesh light's bounds) must lie above its tangent plane.
bool lightCanReach(vec3 position, vec3 normal, GpuLight light) {
  if (light.vplInfo.w != 0) {
    // A mesh light: some corner of its bounds lies above the tangent plane whenever any of its
    // points does.
    for (int c = 0; c < 8; ++c) {
      vec3 corner =
          mix(light.corners[0].xyz, light.corners[1].xyz, vec3(c & 1, (c >> 1) & 1, c >> 2));
      if (dot(corner - position, normal) > 0.0) return true;
    }
    return false;
  }
  if (dot(position - light.corners[0].xyz, light.normalArea.xyz) <= 0.0) return false;
  for (int c = 0; c < 4; ++c) {
    if (dot(light.corners[c].xyz - position, normal) > 0.0) return true;
  }
  return false;
}

// Whether no VPL of a quad light can light the point (false for a mesh light): the quad lies
// behind the point's tangent plane, or the point behind the quad's emitting side. Both hold for
// every VPL when they hold for the corners, of which the VPLs are convex combinations; a margin of
// 1e-4 of the distance keeps the VPLs' rounding from tipping a corner case (a point in the light's
// plane) the other way. Every such VPL's bounded form factor is then exactly zero (vplIncident):
// the trace counts them visible without a ray (visibility_clear.comp) and the gather leaves them
// out.
bool lightCannotLight(vec3 position, vec3 normal, GpuLight light) {
  if (light.vplInfo.w != 0) return false;
  bool behindPoint = true;
  bool pointBehindLight = true;
  for (int i = 0; i < 4; ++i) {
    vec3 towardsCorner = light.corners[i].xyz - position;
    float margin = 1e-4 * length(towardsCorner);
    behindPoint = behindPoint && dot(towardsCorner, normal) < -margin;
    pointBehindLight = pointBehindLight && dot(towardsCorner, light.normalArea.xyz) > margin;
  }
  return behindPoint || pointBehindLight;
}

bool facesAnyLight(vec3 position, vec3 normal, int lightCount) {
  for (int l = 0; l < lightCount; ++l) {
    if (lightCanReach(position, normal, lights[l])) return true;
  }
  return false;
}

float distanceToSegment(vec3 position, vec3 from, vec3 to) {
  vec3 along = to - from;
  float t = clamp(dot(position - from, along) / max(dot(along, along), 1e-20), 0.0, 1.0);
  return distance(position, from + t * along);
}

// Distance from a point to the nearest point of a light: of a quad light's (convex, planar)
// quad, of a mesh light's bounds.
float distanceToLight(vec3 position, GpuLight light) {
  if (light.vplInfo.w != 0) {
    vec3 outside = max(max(light.corners[0].xyz - position, position - light.corners[1].xyz), 0.0);
    return length(outside);
  }
  vec3 normal = light.normalArea.xyz;
  bool inside = true;
  float edgeDistance = 1e30;
  for (int c = 0; c < 4; ++c) {
    vec3 from = light.corners[c].xyz;
    vec3 to = light.corners[(c + 1) % 4].xyz;
    // Inside when the point projects onto the same side of every edge; either winding.
    inside = inside && dot(cross(to - from, position - from), normal) *
                               dot(cross(to - from, light.corners[(c + 2) % 4].xyz - from),
                                   normal) >= 0.0;
    edgeDistance = min(edgeDistance, distanceToSegment(position, from, to));
  }
  return inside ? abs(dot(position - light.corners[0].xyz, normal)) : edgeDistance;
}

// The nearer of `nearest` and the distance to `light`, when the light can reach the point. The
// caller loops over the lights, reading each once for all its points: llvmpipe pays for every read
// of a storage buffer, and the light is the same for them all.
float nearerReachingLight(float nearest, vec3 position, vec3 normal, GpuLight light) {
  return lightCanReach(position, normal, light) ? min(nearest, distanceToLight(position, light))
                                                : nearest;
}
