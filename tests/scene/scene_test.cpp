#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "image/image.h"
#include "test_files.h"

namespace penumbra {
namespace {

constexpr std::string_view kTrianglePly = R"(ply
format ascii 1.0
element vertex 3
property float x
property float y
property float z
element face 1
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
)"
                                          "3 0 1 2\n";

// Three objects sharing one model: one with `mat red` and an animation, one with a textured
// material whose texture the light uses too, and one with no material at all.
constexpr std::string_view kScene = R"(material red
  dif 1 0 0
end
material glow
  emit 2 3 4
  tex screen.png
end
material tinted
  dif 0.5 0.5 0.5
  tex screen.png
end
material plain
  dif 0.25 0.5 1
end
area_light panel
  pos1 -1 2 -1
  pos2 1 2 -1
  pos3 1 2 1
  pos4 -1 2 1
  at 0 0 0
  mat glow
end
area_light second
  pos1 -1 3 -1
  pos2 1 3 -1
  pos3 1 3 1
  pos4 -1 3 1
  mat plain
end
camera cam
  pos 0 1 5
  at 0 1 0
  screen_size 101 61
end
object tri.ply
  translate 0 0 -3
  anim translate 1 0 0 0.1
  mat red
end
object tri.ply
  mat tinted
end
object tri.ply
  normals flat
end
)";

std::filesystem::path writeSceneFiles(const std::filesystem::path& directory,
                                      std::string_view sceneText) {
  test::writeFile(directory, "tri.ply", kTrianglePly);
  saveImage(Image(4, 2, glm::vec4(0.5f)), directory / "screen.png");
  return test::writeFile(directory, "test.scene", sceneText);
}

Scene loadSceneText(const std::filesystem::path& directory, std::string_view sceneText) {
  const auto file = writeSceneFiles(directory, sceneText);
  return loadScene(parseSceneFile(file));
}

TEST(SceneLoad, MaterialsTexturesLightsAndCamera) {
  const Scene scene = loadSceneText(test::scratchDirectory(), kScene);
  ASSERT_EQ(scene.objects.size(), 3u);
  // One texture file named by a light's material and a surface material: loaded once.
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0]->size(), glm::ivec2(4, 2));

  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].name, "panel");
  EXPECT_EQ(scene.lights[0].emission, glm::vec3(2, 3, 4));
  EXPECT_EQ(scene.lights[0].texture, 0);
  EXPECT_EQ(scene.lights[0].quad.normal, glm::vec3(0, -1, 0));        // towards `at`
  EXPECT_EQ(scene.lights[1].emission, glm::vec3(0.25f, 0.5f, 1.0f));  // no `emit`: E = dif
  EXPECT_EQ(scene.lights[1].texture, -1);

  const SurfaceMaterial& red = scene.materials[scene.objects[0].meshMaterial[0]];
  EXPECT_EQ(red.diffuse, glm::vec3(1, 0, 0));
  EXPECT_EQ(red.texture, -1);
  const SurfaceMaterial& tinted = scene.materials[scene.objects[1].meshMaterial[0]];
  EXPECT_EQ(tinted.diffuse, glm::vec3(0.5f));
  EXPECT_EQ(tinted.texture, 0);
  const SurfaceMaterial& fallback = scene.materials[scene.objects[2].meshMaterial[0]];
  EXPECT_EQ(fallback.diffuse, glm::vec3(0.8f));
  EXPECT_EQ(fallback.specular, glm::vec3(0.0f));
  EXPECT_EQ(fallback.texture, -1);
  // Only materials some object uses become surface materials.
  EXPECT_EQ(scene.materials.size(), 3u);

  EXPECT_EQ(scene.camera.position, glm::vec3(0, 1, 5));
  EXPECT_EQ(scene.camera.size, glm::ivec2(101, 61));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(SceneFrame, AnimationMovesTheObject) {
  const Scene scene = loadSceneText(test::scratchDirectory(), kScene);
  const glm::vec3 model[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (const int frame : {0, 10}) {
    const FrameGeometry geometry = buildFrameGeometry(scene, frame);
    ASSERT_EQ(geometry.triangles.size(), 3u);
    const int red = scene.objects[0].meshMaterial[0];
    bool found = false;
    for (std::size_t t = 0; t < geometry.triangles.size(); ++t) {
      if (geometry.triangleMaterial[t] != red)
        continue;
      found = true;
      // translate 0 0 -3, then the offset (1,0,0) * sin(0.1 * frame).
      const glm::vec3 offset(static_cast<float>(std::sin(0.1 * frame)), 0.0f, -3.0f);
      for (int corner = 0; corner < 3; ++corner) {
        const glm::vec3 actual = geometry.positions[geometry.triangles[t][corner]];
        // One float multiply-add per coordinate.
        EXPECT_NEAR(glm::distance(actual, model[corner] + offset), 0.0f, 1e-6f) << frame;
        EXPECT_EQ(geometry.normals[geometry.triangles[t][corner]], glm::vec3(0, 0, 1));
      }
    }
    EXPECT_TRUE(found);
  }
}

TEST(SceneFrame, BatchesAreContiguousPerMaterial) {
  const Scene scene = loadSceneText(test::scratchDirectory(), kScene);
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  ASSERT_EQ(geometry.batches.size(), 3u);
  std::uint32_t next = 0;
  for (const FrameGeometry::Batch& batch : geometry.batches) {
    EXPECT_EQ(batch.firstTriangle, next);
    next += batch.triangleCount;
    for (std::uint32_t t = batch.firstTriangle; t < batch.firstTriangle + batch.triangleCount; ++t)
      EXPECT_EQ(geometry.triangleMaterial[t], batch.material);
  }
  EXPECT_EQ(next, geometry.triangles.size());
  EXPECT_EQ(geometry.positions.size(), geometry.normals.size());
  EXPECT_EQ(geometry.positions.size(), geometry.uvs.size());
  // Bounds cover the triangles (z from -3 to 0) and both lights (y up to 3, x from -1).
  EXPECT_EQ(geometry.boundsMin, glm::vec3(-1, 0, -3));
  EXPECT_EQ(geometry.boundsMax, glm::vec3(1, 3, 1));
}

// A batch's box is that of its own triangles' corners, exactly (the corners are copied).
TEST(SceneFrame, EachBatchKnowsTheBoxOfItsTriangles) {
  const Scene scene = loadSceneText(test::scratchDirectory(), kScene);
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  ASSERT_FALSE(geometry.batches.empty());
  for (const FrameGeometry::Batch& batch : geometry.batches) {
    glm::vec3 low(std::numeric_limits<float>::infinity());
    glm::vec3 high(-std::numeric_limits<float>::infinity());
    for (std::uint32_t t = batch.firstTriangle; t < batch.firstTriangle + batch.triangleCount;
         ++t) {
      for (int corner = 0; corner < 3; ++corner) {
        low = glm::min(low, geometry.positions[geometry.triangles[t][corner]]);
        high = glm::max(high, geometry.positions[geometry.triangles[t][corner]]);
      }
    }
    EXPECT_EQ(batch.boundsMin, low) << "material " << batch.material;
    EXPECT_EQ(batch.boundsMax, high) << "material " << batch.material;
  }
}

// The G-buffer tells which mesh a pixel shows from the first vertex of its triangle
// (gbuffer_surface.frag), so each mesh's vertices must follow one another from its first.
TEST(SceneFrame, MeshFirstVerticesStartEachMeshsRunOfVertices) {
  const Scene scene = loadSceneText(test::scratchDirectory(), kScene);
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  std::vector<std::uint32_t> expected;
  std::uint32_t next = 0;
  for (const SceneObject& object : scene.objects) {
    for (const Mesh& mesh : object.model.meshes) {
      expected.push_back(next);
      next += static_cast<std::uint32_t>(mesh.positions.size());
    }
  }
  ASSERT_GE(expected.size(), 2u);
  EXPECT_EQ(geometry.meshFirstVertices, expected);
  EXPECT_EQ(next, geometry.positions.size());
  const auto meshOf = [&](std::uint32_t vertex) {
    return std::upper_bound(expected.begin(), expected.end(), vertex) - expected.begin();
  };
  for (const glm::uvec3& triangle : geometry.triangles) {
    EXPECT_EQ(meshOf(triangle[1]), meshOf(triangle[0]));
    EXPECT_EQ(meshOf(triangle[2]), meshOf(triangle[0]));
  }
}

TEST(SceneFrame, StanfordBunnyLoadsWithItsPublishedBoundsAndCleanNormals) {
  SceneDesc desc;
  desc.file = test::scratchDirectory() / "bunny.scene";
  ObjectDesc object;
  object.model = test::sourceDirectory() / "scenes" / "assets" / "bunny.ply";
  object.animations.push_back({Animation::Kind::Rotate, {0, 1, 0}, 0.02f});
  desc.objects.push_back(object);
  const Scene scene = loadScene(desc);
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);

  EXPECT_EQ(geometry.triangles.size(), 3674u);
  ASSERT_EQ(geometry.batches.size(), 1u);
  // The bounding box given by ../shared/assets/README.md, printed to 6 decimals.
  const glm::vec3 readmeMin(-4.958475f, -0.003149f, -3.729833f);
  const glm::vec3 readmeMax(4.948850f, 9.654748f, 3.810639f);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(geometry.boundsMin[axis], readmeMin[axis], 1e-6f);
    EXPECT_NEAR(geometry.boundsMax[axis], readmeMax[axis], 1e-6f);
  }
  for (const glm::vec3& normal : geometry.normals)
    ASSERT_NEAR(glm::length(normal), 1.0f, 1e-5f);  // float normalisation, then a rotation
}

TEST(SceneCamera, CentreRayIsTheViewDirection) {
  Camera camera;
  camera.position = {1, 2, 3};
  camera.target = {-2, 0.5f, -1};
  camera.size = {101, 61};
  const glm::vec3 view = glm::normalize(camera.target - camera.position);
  // The same direction computed two ways in float.
  EXPECT_NEAR(glm::distance(camera.rayDirection(50, 30), view), 0.0f, 1e-6f);
}

TEST(SceneCamera, RaysAgreeWithTheMatrices) {
  Camera camera;
  camera.position = {1, 2, 3};
  camera.target = {-2, 0.5f, -1};
  camera.up = {0, 1, 0.2f};
  camera.fovyDegrees = 60.0f;
  camera.size = {160, 90};
  const glm::mat4 clipFromWorld = camera.clipFromView() * camera.viewFromWorld();
  for (const glm::ivec2 pixel : {glm::ivec2(0, 0), glm::ivec2(159, 0), glm::ivec2(17, 80)}) {
    const glm::vec3 direction = camera.rayDirection(pixel.x, pixel.y);
    EXPECT_NEAR(glm::length(direction), 1.0f, 1e-6f);  // float normalisation
    const glm::vec4 clip = clipFromWorld * glm::vec4(camera.position + 7.0f * direction, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const glm::vec2 expected(2.0f * (static_cast<float>(pixel.x) + 0.5f) / 160.0f - 1.0f,
                             1.0f - 2.0f * (static_cast<float>(pixel.y) + 0.5f) / 90.0f);
    // Two float paths through a projection: well under a hundredth of a pixel.
    EXPECT_NEAR(ndc.x, expected.x, 1e-5f);
    EXPECT_NEAR(ndc.y, expected.y, 1e-5f);
  }
}

// The G-buffer leaves out the batches whose box the camera cannot see (gbuffer.cpp): a box is
// kept whenever any of it may be in view, and dropped only when it lies wholly beyond one plane
// of the view volume.
TEST(SceneCamera, MaySeeABoxUnlessItLiesWhollyOutsideOnePlaneOfTheView) {
  Camera camera;
  camera.position = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.fovyDegrees = 90.0f;  // the view's sides at 45 degrees: x = +-z and y = +-z
  camera.nearPlane = 1.0f;
  camera.farPlane = 10.0f;
  camera.size = {64, 64};
  const glm::vec3 half(0.25f);
  // In view; straddling a side; straddling the near and the far plane; enclosing the eye.
  for (const glm::vec3 centre :
       {glm::vec3(0, 0, -5), glm::vec3(5, 0, -5), glm::vec3(0, 0, -1), glm::vec3(0, 0, -10)})
    EXPECT_TRUE(camera.maySeeBox(centre - half, centre + half)) << centre.x << " " << centre.z;
  EXPECT_TRUE(camera.maySeeBox(glm::vec3(-20), glm::vec3(20)));
  // Behind the eye, nearer than the near plane, beyond the far plane, and off each side.
  for (const glm::vec3 centre :
       {glm::vec3(0, 0, 5), glm::vec3(0, 0, -0.5f), glm::vec3(0, 0, -11), glm::vec3(6, 0, -5),
        glm::vec3(-6, 0, -5), glm::vec3(0, 6, -5), glm::vec3(0, -6, -5)})
    EXPECT_FALSE(camera.maySeeBox(centre - half, centre + half)) << centre.x << " " << centre.z;
}

TEST(SceneCamera, TurningAboutTheTargetMovesOnlyTheEyeAroundUp) {
  Camera camera;
  camera.position = {1, 2, 5};
  camera.target = {1, 0, 1};
  camera.up = {0, 2, 0};  // not unit: the turn normalises it
  camera.fovyDegrees = 30.0f;
  const Camera turned = camera.turnedAboutTarget(glm::half_pi<float>());
  // A quarter turn about +y takes the eye's offset from the target, (0, 2, 4), to (4, 2, 0); a
  // rotation matrix in float: a few ulps of the offset.
  EXPECT_NEAR(glm::distance(turned.position, glm::vec3(5, 2, 1)), 0.0f, 1e-5f);
  EXPECT_EQ(turned.target, camera.target);
  EXPECT_EQ(turned.up, camera.up);
  EXPECT_EQ(turned.fovyDegrees, camera.fovyDegrees);
  // Four quarter turns come back to the start.
  Camera around = camera;
  for (int step = 0; step < 4; ++step)
    around = around.turnedAboutTarget(glm::half_pi<float>());
  EXPECT_NEAR(glm::distance(around.position, camera.position), 0.0f, 1e-5f);
}

TEST(SceneCamera, DefaultCameraFramesTheScene) {
  std::string text(kScene);
  text.erase(text.find("camera cam"), text.find("object tri.ply") - text.find("camera cam"));
  const Scene scene = loadSceneText(test::scratchDirectory(), text);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("camera"), std::string::npos);

  const Camera& camera = scene.camera;
  const FrameGeometry geometry = buildFrameGeometry(scene, 0);
  EXPECT_GT(camera.position.z, geometry.boundsMax.z);
  EXPECT_EQ(camera.target, 0.5f * (geometry.boundsMin + geometry.boundsMax));
  const glm::mat4 clipFromWorld = camera.clipFromView() * camera.viewFromWorld();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point((corner & 1) ? geometry.boundsMax.x : geometry.boundsMin.x,
                          (corner & 2) ? geometry.boundsMax.y : geometry.boundsMin.y,
                          (corner & 4) ? geometry.boundsMax.z : geometry.boundsMin.z);
    const glm::vec4 clip = clipFromWorld * glm::vec4(point, 1.0f);
    ASSERT_GT(clip.w, 0.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GT(ndc[axis], -1.0f) << corner;
      EXPECT_LT(ndc[axis], 1.0f) << corner;
    }
  }
}

// Column 0: any column (the error is at a block's first token).
void expectSceneErrorAt(const std::filesystem::path& directory, std::string_view text,
                        const std::string& fragment, int line, int column = 0) {
  const SceneDesc desc = parseSceneFile(writeSceneFiles(directory, text));
  try {
    loadScene(desc);
    FAIL() << "the scene loaded";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.where().line, line) << error.what();
    if (column > 0) {
      EXPECT_EQ(error.where().column, column) << error.what();
    }
    EXPECT_NE(error.message().find(fragment), std::string::npos) << error.what();
  }
}

TEST(SceneErrors, CarryTheLocationOfTheCause) {
  // The parser already rejects missing files; these exist but cannot be read.
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "broken.ply", "ply\nnot a header\n");
  test::writeFile(directory, "broken.png", "not a PNG");
  test::writeFile(directory, "clip.mp4", "not a video");
  expectSceneErrorAt(directory, "object broken.ply\nend\n", "broken.ply", 1);
  // A texture or a video is at its `tex` value, not at its material's first line.
  expectSceneErrorAt(directory, "material m\n  tex broken.png\nend\nobject tri.ply\n  mat m\nend\n",
                     "broken.png", 2, 7);
  expectSceneErrorAt(directory,
                     "object tri.ply\nend\nmaterial clip\n  tex clip.mp4\nend\n"
                     "area_light tv\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 1 1 0\n  pos4 0 1 0\n"
                     "  mat clip\nend\n",
                     "clip.mp4", 4, 7);
}

TEST(SceneErrors, ModelTextureFailureIsAtTheObject) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "broken.png", "not a PNG");
  test::writeFile(directory, "textured.mtl", "newmtl skin\nKd 1 1 1\nmap_Kd broken.png\n");
  test::writeFile(directory, "textured.obj",
                  "mtllib textured.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl skin\nf 1 2 3\n");
  expectSceneErrorAt(directory, "\nobject textured.obj\nend\n", "broken.png", 2);
}

}  // namespace
}  // namespace penumbra
