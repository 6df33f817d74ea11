#include "emitter_shapes.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <vector>

namespace penumbra::test {

namespace {

double chord(double radius, double angle) {
  return 2.0 * radius * std::sin(0.5 * angle);
}

// The UV sphere both writers give: vertex (ring r, segment s) at r * segments + s, r = 0..rings
// from the north pole (the poles repeat per segment), as unit directions; triangles of 0-based
// indices, counter-clockwise seen from outside, one per segment in the pole bands.
struct UvSphere {
  std::vector<std::array<double, 3>> directions;
  std::vector<std::array<int, 3>> triangles;
};

UvSphere uvSphere(int rings, int segments) {
  UvSphere sphere;
  for (int r = 0; r <= rings; ++r) {
    const double polar = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * std::numbers::pi * s / segments;
      sphere.directions.push_back({std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                   std::sin(polar) * std::sin(azimuth)});
    }
  }
  const auto index = [segments](int r, int s) { return r * segments + s % segments; };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = index(r, s);
      const int b = index(r, s + 1);
      const int c = index(r + 1, s + 1);
      const int d = index(r + 1, s);
      if (r > 0)
        sphere.triangles.push_back({a, b, c});
      if (r < rings - 1)
        sphere.triangles.push_back({a, c, d});
    }
  }
  return sphere;
}

}  // namespace

std::string sphereObj(double radius, int rings, int segments) {
  const UvSphere sphere = uvSphere(rings, segments);
  std::ostringstream obj;
  obj.precision(17);
  for (const auto& [x, y, z] : sphere.directions) {
    obj << "v " << radius * x << ' ' << radius * y << ' ' << radius * z << '\n';
    obj << "vn " << x << ' ' << y << ' ' << z << '\n';
  }
  for (const std::array<int, 3>& triangle : sphere.triangles) {
    obj << 'f';
    for (const int corner : triangle)
      obj << ' ' << corner + 1 << "//" << corner + 1;
    obj << '\n';
  }
  return obj.str();
}

std::string sphereBinaryPly(double radius, int rings, int segments) {
  const UvSphere sphere = uvSphere(rings, segments);
  std::ostringstream ply;
  ply << "ply\nformat binary_little_endian 1.0\nelement vertex " << sphere.directions.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
      << sphere.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  const auto write = [&ply](auto value) {
    ply.write(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  for (const std::array<double, 3>& direction : sphere.directions) {
    for (const double coordinate : direction)
      write(static_cast<float>(radius * coordinate));
  }
  for (const std::array<int, 3>& triangle : sphere.triangles) {
    write(static_cast<unsigned char>(3));
    for (const int corner : triangle)
      write(static_cast<std::int32_t>(corner));
  }
  return ply.str();
}

double sphereObjArea(double radius, int rings, int segments) {
  const double turn = 2.0 * std::numbers::pi / segments;
  double area = 0.0;
  for (int r = 0; r < rings; ++r) {
    const double polar0 = std::numbers::pi * r / rings;
    const double polar1 = std::numbers::pi * (r + 1) / rings;
    // A band's cell is a planar isosceles trapezoid between chords on two rings.
    const double top = chord(radius * std::sin(polar0), turn);
    const double bottom = chord(radius * std::sin(polar1), turn);
    const double dy = radius * (std::cos(polar0) - std::cos(polar1));
    const double dr = radius * (std::sin(polar1) - std::sin(polar0)) * std::cos(0.5 * turn);
    const double slant = std::sqrt(dy * dy + dr * dr);
    area += segments * 0.5 * (top + bottom) * slant;
  }
  return area;
}

std::string curvedScreenObj(double radius, double halfAngle, double height, int columns) {
  std::ostringstream obj;
  obj.precision(17);
  for (int c = 0; c <= columns; ++c) {
    const double u = static_cast<double>(c) / columns;
    const double angle = -halfAngle + 2.0 * halfAngle * u;
    const double x = radius * std::sin(angle);
    const double z = -radius * std::cos(angle);
    for (int row = 0; row < 2; ++row) {
      obj << "v " << x << ' ' << height * row << ' ' << z << '\n';
      obj << "vt " << u << ' ' << row << '\n';
      obj << "vn " << -x / radius << " 0 " << -z / radius << '\n';
    }
  }
  for (int c = 0; c < columns; ++c) {
    const int a = 2 * c + 1;  // bottom left, seen from the axis
    const int b = a + 2;      // bottom right
    obj << "f " << a << '/' << a << '/' << a << ' ' << b << '/' << b << '/' << b << ' ' << b + 1
        << '/' << b + 1 << '/' << b + 1 << '\n';
    obj << "f " << a << '/' << a << '/' << a << ' ' << b + 1 << '/' << b + 1 << '/' << b + 1 << ' '
        << a + 1 << '/' << a + 1 << '/' << a + 1 << '\n';
  }
  return obj.str();
}

double curvedScreenObjArea(double radius, double halfAngle, double height, int columns) {
  return columns * chord(radius, 2.0 * halfAngle / columns) * height;
}

}  // namespace penumbra::test
