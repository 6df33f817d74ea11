// The shading every renderer mode computes (docs/shading.md): the diffuse term rho/pi plus the
// normalised Phong lobe, times the VPL's radiance and its bounded form factor.

// Light arriving from one VPL, as radiance scaled by the geometric term, before the BRDF:
// L_e * pi * A cos_x cos_y / (pi r^2 + A). The bounded form (the disc-to-point form factor)
// keeps the 1/r^2 of a point light from exploding next to the light.
vec3 vplIncident(vec3 position, vec3 normal, vec3 vplPosition, vec3 vplNormal, float vplArea,
                 vec3 vplRadiance, out vec3 towardsLight) {
  vec3 d = vplPosition - position;
  float distanceSquared = max(dot(d, d), 1e-12);
  towardsLight = d * inversesqrt(distanceSquared);
  float cosSurface = max(dot(normal, towardsLight), 0.0);
  float cosLight = max(-dot(vplNormal, towardsLight), 0.0);
  return vplRadiance * (kPi * vplArea * cosSurface * cosLight / (kPi * distanceSquared + vplArea));
}

// f_r = rho/pi + k_s (n+2)/(2 pi) cos^n(alpha), alpha between the mirrored light direction and
// the direction to the eye.
vec3 phongBrdf(vec3 albedo, vec3 specular, float shininess, vec3 normal, vec3 towardsLight,
               vec3 towardsEye) {
  vec3 diffuse = albedo / kPi;
  if (all(equal(specular, vec3(0.0)))) return diffuse;
  float cosAlpha = max(dot(reflect(-towardsLight, normal), towardsEye), 0.0);
  // pow(0, 0) is undefined in GLSL; cos^0 is 1 everywhere.
  float lobe = shininess > 0.0 ? pow(cosAlpha, shininess) : 1.0;
  return diffuse + specular * ((shininess + 2.0) / (2.0 * kPi)) * lobe;
}
