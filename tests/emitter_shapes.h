#pragma once
// Meshes of emitters that tests write as OBJ files: the quad the area_light tests use, a sphere
// and a curved screen (a section of a cylinder), with their exact areas for comparison.

#include <string>

namespace penumbra::test {

// The quad (-1,1.5,-1) (1,1.5,-1) (1,1.5,1) (-1,1.5,1) as two triangles facing -y, with the
// texture coordinates area_light gives the same corners (pos1..pos4 in this order, `at` below).
inline constexpr const char* kCeilingQuadObj =
    "v -1 1.5 -1\nv 1 1.5 -1\nv 1 1.5 1\nv -1 1.5 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 -1 0\n"
    "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
inline constexpr const char* kCeilingQuadCorners =
    "  pos1 -1 1.5 -1\n  pos2 1 1.5 -1\n  pos3 1 1.5 1\n  pos4 -1 1.5 1\n  at 0 0 0\n";

// A UV sphere around the origin with outward normals: `rings` bands of latitude, `segments`
// of longitude.
std::string sphereObj(double radius, int rings, int segments);
// The exact area of that polyhedron (its quads and the triangles at the poles).
double sphereObjArea(double radius, int rings, int segments);
// The same sphere's positions and triangles as a binary PLY (no normals), for spheres of
// hundreds of thousands of triangles, which load far faster in binary than as OBJ text.
std::string sphereBinaryPly(double radius, int rings, int segments);

// A screen curved about the y axis: the part of the cylinder of `radius` around the y axis
// within `halfAngle` radians of -z, from y = 0 to `height`, in `columns` strips; its normals
// face the axis (the viewer at the centre), its u runs along the arc and v up.
std::string curvedScreenObj(double radius, double halfAngle, double height, int columns);
// The exact area of that mesh: `columns` flat strips of chord width.
double curvedScreenObjArea(double radius, double halfAngle, double height, int columns);

}  // namespace penumbra::test
