// Needs the `lights` buffer declared before the include.
// Whether any light can reach a point: it must lie in front of a quad light's plane, and at
// least one corner of the light (of a mesh light's bounds) must lie above its tangent plane.
bool facesAnyLight(vec3 position, vec3 normal, int lightCount) {
  for (int l = 0; l < lightCount; ++l) {
    GpuLight light = lights[l];
    if (light.vplInfo.w != 0) {
      // A mesh light: some corner of its bounds lies above the tangent plane whenever any of
      // its points does.
      for (int c = 0; c < 8; ++c) {
        vec3 corner = mix(light.corners[0].xyz, light.corners[1].xyz,
                          vec3(c & 1, (c >> 1) & 1, c >> 2));
        if (dot(corner - position, normal) > 0.0) return true;
      }
      continue;
    }
    if (dot(position - light.corners[0].xyz, light.normalArea.xyz) <= 0.0) continue;
    for (int c = 0; c < 4; ++c) {
      if (dot(light.corners[c].xyz - position, normal) > 0.0) return true;
    }
  }
  return false;
}
