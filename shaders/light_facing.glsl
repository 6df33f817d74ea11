// Needs the `lights` buffer declared before the include.
// Whether any light can reach a point: it must lie in front of the light's plane, and at least
// one corner of the light must lie above the point's tangent plane.
bool facesAnyLight(vec3 position, vec3 normal, int lightCount) {
  for (int l = 0; l < lightCount; ++l) {
    GpuLight light = lights[l];
    if (dot(position - light.corners[0].xyz, light.normalArea.xyz) <= 0.0) continue;
    for (int c = 0; c < 4; ++c) {
      if (dot(light.corners[c].xyz - position, normal) > 0.0) return true;
    }
  }
  return false;
}
