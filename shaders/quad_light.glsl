// Quad light geometry in GLSL, the same maps as src/scene/area_light.cpp.

// P(u,v) = (1-v)((1-u) p1 + u p2) + v((1-u) p4 + u p3)
vec3 quadPointAt(vec3 p1, vec3 p2, vec3 p3, vec3 p4, vec2 uv) {
  return mix(mix(p1, p2, uv.x), mix(p4, p3, uv.x), uv.y);
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// Inverse of quadPointAt for a point on the quad's plane. Writing P - p1 = u e + v f + u v g
// in 2D coordinates of the plane, eliminating v gives a quadratic in u; v then follows.
vec2 quadUvAt(vec3 p1, vec3 p2, vec3 p3, vec3 p4, vec3 normal, vec3 point) {
  vec3 axisX = normalize(p2 - p1);
  vec3 axisY = cross(normal, axisX);
  vec2 e = vec2(dot(p2 - p1, axisX), dot(p2 - p1, axisY));
  vec2 f = vec2(dot(p4 - p1, axisX), dot(p4 - p1, axisY));
  vec3 g3 = p1 - p2 + p3 - p4;
  vec2 g = vec2(dot(g3, axisX), dot(g3, axisY));
  vec2 h = vec2(dot(point - p1, axisX), dot(point - p1, axisY));
  float a = -cross2(e, g);
  float b = cross2(h, g) - cross2(e, f);
  float c = cross2(h, f);
  float u;
  if (abs(a) < 1e-7 * abs(b)) {
    u = -c / b;
  } else {
    float root = sqrt(max(b * b - 4.0 * a * c, 0.0));
    float u1 = (-b + root) / (2.0 * a);
    float u2 = (-b - root) / (2.0 * a);
    u = (u1 >= -1e-3 && u1 <= 1.0 + 1e-3) ? u1 : u2;
  }
  vec2 across = f + u * g;
  float v = dot(h - u * e, across) / dot(across, across);
  return vec2(u, v);
}
