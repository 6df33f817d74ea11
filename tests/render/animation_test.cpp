// Animation on the GPU: an `anim translate` object lands where its transform puts it at each
// frame, and a video light shows the video frame of each rendered frame, or of the time it is
// given.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "image/video_writer.h"
#include "render/frame.h"
#include "render/render_test_scenes.h"
#include "scene/transform.h"
#include "test_files.h"

namespace penumbra {
namespace {

// A 0.4 x 0.4 square facing +z, centred on its origin.
constexpr const char* kSquareObj =
    "v -0.2 -0.2 0\nv 0.2 -0.2 0\nv 0.2 0.2 0\nv -0.2 0.2 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n";

// The materials, a light behind the camera (so that a lit square is the only thing in view, on
// black) and the camera, looking down -z at the origin from 4 away.
constexpr const char* kSquareStage =
    "material white\n  dif 1 1 1\nend\n"
    "material glow\n  emit 1 1 1\nend\n"
    "area_light front\n"
    "  pos1 -2 -2 5\n  pos2 2 -2 5\n  pos3 2 2 5\n  pos4 -2 2 5\n"
    "  at 0 0 0\n  mat glow\nend\n"
    "camera front\n  pos 0 0 4\n  at 0 0 0\n  screen_size 64 64\nend\n";

// The square at `place` ("x y z", or none for the origin), offset by `amplitude` * sin(pi/30 *
// frame): none at frame 0, all of it at frame 15.
std::string oscillatingSquare(const std::string& amplitude, const std::string& place = "") {
  return "object square.obj\n  mat white\n" + (place.empty() ? "" : "  translate " + place + "\n") +
         "  anim translate " + amplitude + " " + std::to_string(std::numbers::pi / 30.0) +
         "\nend\n";
}

const std::string kOscillatingSquare = kSquareStage + oscillatingSquare("1 0.5 0");

// Where the camera projects `world`, in pixels from the image's top-left corner (pixel (i, j)
// covers [i, i+1) x [j, j+1)).
glm::vec2 projectToPixels(const Camera& camera, glm::vec3 world) {
  const glm::vec4 clip = camera.clipFromView() * camera.viewFromWorld() * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * static_cast<float>(camera.size.x),
          (0.5f - ndc.y * 0.5f) * static_cast<float>(camera.size.y)};
}

// The mean of the centres of the pixels that show anything.
glm::vec2 silhouetteCentre(const Image& image) {
  glm::dvec2 sum(0.0);
  int count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y).r > 0.0f) {
        sum += glm::dvec2(x + 0.5, y + 0.5);
        ++count;
      }
    }
  }
  EXPECT_GT(count, 0) << "nothing visible";
  return glm::vec2(sum / static_cast<double>(std::max(count, 1)));
}

TEST(Animation, TranslatedObjectAppearsWhereItsTransformPutsIt) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "square.obj", kSquareObj);
  Scene scene = test::loadSceneText(directory, kOscillatingSquare);
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 16;

  for (const int frame : {0, 15}) {
    renderer.render(frame, settings);
    const float offset = static_cast<float>(std::sin(std::numbers::pi / 30.0 * frame));
    const glm::vec3 expectedCentre = glm::vec3(1.0f, 0.5f, 0.0f) * offset;
    const glm::vec2 expected = projectToPixels(scene.camera, expectedCentre);
    const glm::vec2 found = silhouetteCentre(renderer.readRadiance());
    // The square faces the camera squarely, so its projection is a square whose centre is the
    // projected centre. Rasterisation covers the pixels whose centres lie inside it, which moves
    // the centre of the covered pixels by up to half a pixel on each axis. The animation moves
    // the square by about 19 x 10 pixels from frame 0 to frame 15. 0.05 for float rounding.
    EXPECT_NEAR(found.x, expected.x, 0.55f) << "frame " << frame;
    EXPECT_NEAR(found.y, expected.y, 0.55f) << "frame " << frame;
  }
}

// The G-buffer leaves out what its view cannot see by each batch's box (Camera::maySeeBox), and an
// animated object's box moves with it: a square out of view at frame 0 (x = 3, the view's half
// width at its distance about 1.7) that moves to the middle at frame 15 is drawn there by a
// renderer that drew frame 0 first.
TEST(Animation, ObjectMovingIntoViewIsDrawnWhereItArrives) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "square.obj", kSquareObj);
  Scene scene = test::loadSceneText(directory, kSquareStage + oscillatingSquare("-3 0 0", "3 0 0"));
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 16;
  renderer.render(0, settings);
  renderer.render(15, settings);
  const glm::vec2 found = silhouetteCentre(renderer.readRadiance());
  // As in TranslatedObjectAppearsWhereItsTransformPutsIt: half a pixel of rasterisation, 0.05 for
  // float rounding.
  const glm::vec2 expected = projectToPixels(scene.camera, glm::vec3(0.0f));
  EXPECT_NEAR(found.x, expected.x, 0.55f);
  EXPECT_NEAR(found.y, expected.y, 0.55f);
}

// Frame i of the test video: the top half's red and the bottom half's green encode i in 8-bit
// codes 16 apart.
int topRedCode(int frame) {
  return 16 + 16 * frame;
}
int bottomGreenCode(int frame) {
  return 240 - 16 * frame;
}

float linearOfCode(int code) {
  return srgbToLinear(static_cast<float>(code) / 255.0f);
}

TEST(VideoLight, ShowsTheVideoFrameOfEachRenderedFrame) {
  const auto directory = test::scratchDirectory();
  constexpr int kFrames = 6;  // more than the upload ring's slots, so that slots are reused
  {
    VideoOptions options;
    options.nearLossless = true;
    VideoWriter writer(directory / "halves.mp4", {32, 32}, options);
    for (int frame = 0; frame < kFrames; ++frame) {
      Image picture(32, 32);
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
          picture.at(x, y) = y < 16 ? glm::vec4(linearOfCode(topRedCode(frame)), 0, 0, 1)
                                    : glm::vec4(0, linearOfCode(bottomGreenCode(frame)), 0, 1);
        }
      }
      writer.write(picture);
    }
    writer.finish();
  }
  // The light fills the view, upright (pos1 at the bottom left, seen from the front).
  Scene scene = test::loadSceneText(
      directory,
      "material screen\n  emit 2 2 2\n  tex halves.mp4\nend\n"
      "area_light tv\n  pos1 -1 -1 0\n  pos2 1 -1 0\n  pos3 1 1 0\n  pos4 -1 1 0\n"
      "  at 0 0 1\n  mat screen\nend\n"
      "camera c\n  pos 0 0 1.5\n  at 0 0 0\n  screen_size 32 32\nend\n");
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 1;

  // The light's pixels show video frame `videoFrame`.
  const auto expectVideoFrame = [&](int videoFrame, const std::string& context) {
    const Image image = renderer.readRadiance();
    // Pixels well inside each half, away from the edge that bilinear filtering blends.
    const glm::vec4 top = image.at(16, 8);
    const glm::vec4 bottom = image.at(16, 24);
    // 3 codes: the YCbCr round trip moves a flat colour by at most 2 codes; neighbouring frames
    // are 16 codes apart.
    const auto tolerance = [](int code) {
      return 2.0f * (linearOfCode(code + 3) - linearOfCode(code));
    };
    EXPECT_NEAR(top.r, 2.0f * linearOfCode(topRedCode(videoFrame)),
                tolerance(topRedCode(videoFrame)))
        << context;
    EXPECT_NEAR(bottom.g, 2.0f * linearOfCode(bottomGreenCode(videoFrame)),
                tolerance(bottomGreenCode(videoFrame)))
        << context;
    EXPECT_NEAR(top.g, 0.0f, tolerance(0)) << context;
    EXPECT_NEAR(bottom.r, 0.0f, tolerance(0)) << context;
  };

  // Forwards through the ring, then back (a seek in the video).
  for (const int frame : {0, 1, 2, 3, 4, 5, 2}) {
    renderer.render(frame, settings);
    expectVideoFrame(frame, "frame " + std::to_string(frame));
  }
  // The viewer's wall clock: the video's time apart from the animation's. Video frame 4 is shown
  // from 4/30 s to 5/30 s.
  renderer.render(0, settings, 4.5 / 30.0);
  expectVideoFrame(4, "frame 0 with the video at 4.5/30 s");
}

// The oscillating square in front of a static one, for the uploads of each frame.
const std::string kSquareBeforeAStaticOne = kOscillatingSquare +
                                            "object square.obj\n  mat white\n"
                                            "  translate 0 0 -1\n  scale 4 4 1\nend\n";

std::size_t vertexCount(const SceneObject& object) {
  std::size_t count = 0;
  for (const Mesh& mesh : object.model.meshes)
    count += mesh.positions.size();
  return count;
}

std::uint64_t uploadOfFrame(Renderer& renderer, int frame, const RenderSettings& settings) {
  renderer.render(frame, settings);
  return renderer.statistics().sceneUploadBytes;
}

TEST(SceneUpload, StaticSceneUploadsNothingAfterItsFirstFrame) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "square.obj", kSquareObj);
  Scene scene = test::loadSceneText(directory, kSquareBeforeAStaticOne);
  scene.objects.front().desc.animations.clear();
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 16;
  EXPECT_GT(uploadOfFrame(renderer, 0, settings), 0u);
  EXPECT_EQ(uploadOfFrame(renderer, 1, settings), 0u);
  EXPECT_EQ(uploadOfFrame(renderer, 7, settings), 0u);
  // A new VPL count changes the light list (its VPL ranges), and only that: one GpuLight.
  settings.vplsPerLight = 64;
  EXPECT_EQ(uploadOfFrame(renderer, 7, settings), sizeof(gpu::GpuLight));
}

TEST(SceneUpload, AnimatedSceneUploadsOnlyItsTransforms) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "square.obj", kSquareObj);
  Scene scene = test::loadSceneText(directory, kSquareBeforeAStaticOne);
  ASSERT_FALSE(scene.objects[0].desc.animations.empty());
  ASSERT_TRUE(scene.objects[1].desc.animations.empty());
  Renderer renderer(scene, scene.camera.size);
  RenderSettings settings;
  settings.mode = RenderMode::Naive;
  settings.vplsPerLight = 16;
  const std::uint64_t animatedVertexBytes =
      vertexCount(scene.objects[0]) * gpu::kFloatsPerVertex * sizeof(float);
  // The first frame: both squares' world-space vertices and the animated one's object-space copy.
  EXPECT_GT(uploadOfFrame(renderer, 0, settings), 3 * animatedVertexBytes);
  EXPECT_EQ(uploadOfFrame(renderer, 1, settings), sizeof(gpu::GpuObjectTransform));
  EXPECT_EQ(uploadOfFrame(renderer, 15, settings), sizeof(gpu::GpuObjectTransform));
}

// The GPU's transform of an animated object (animate_vertices.comp) gives the frame that the
// CPU's gives: the same object with its transform at that frame made static, whose world-space
// vertices buildFrameGeometry computes and SceneGpu uploads.
TEST(SceneUpload, AnimatedFrameMatchesTheCpuTransform) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "square.obj", kSquareObj);
  // A turn as well as the translation, so that the normals change with the frame.
  const Animation turn{Animation::Kind::Rotate, {0.3f, 1.0f, 0.0f}, 0.07f};
  Scene animated = test::loadSceneText(directory, kSquareBeforeAStaticOne);
  animated.objects[0].desc.animations.push_back(turn);
  Scene baked = test::loadSceneText(directory, kSquareBeforeAStaticOne);
  constexpr int kFrame = 9;
  baked.objects[0].desc.staticTransform = worldFromObject(animated.objects[0].desc, kFrame);
  baked.objects[0].desc.animations.clear();
  RenderSettings settings;
  settings.mode = RenderMode::Hierarchical;
  settings.vplsPerLight = 16;
  Renderer onGpu(animated, animated.camera.size);
  onGpu.render(kFrame, settings);
  Renderer onCpu(baked, baked.camera.size);
  onCpu.render(kFrame, settings);
  const ImageMetrics difference = compareImages(onGpu.readRadiance(), onCpu.readRadiance());
  // The GPU repeats the CPU's operations in glm's order and keeps them from being fused
  // (`precise`); what may still differ is the last bit of a sqrt or a division on another
  // driver, about 1e-7 relative in a vertex, far below a pixel's worth of movement (a wrong
  // transform moves the square by pixels and changes errors by the square's whole radiance).
  EXPECT_LT(difference.maxError, 1e-4) << "rmse " << difference.rmse;
}

// The vertices a frame leaves alone are still right: a frame rendered after others is the frame
// a fresh renderer renders, bit for bit.
TEST(SceneUpload, FrameAfterOthersMatchesAFreshRenderer) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "square.obj", kSquareObj);
  Scene scene = test::loadSceneText(directory, kSquareBeforeAStaticOne);
  RenderSettings settings;
  settings.mode = RenderMode::Hierarchical;
  settings.vplsPerLight = 16;
  Renderer reused(scene, scene.camera.size);
  for (const int frame : {0, 4, 9})
    reused.render(frame, settings);
  Renderer fresh(scene, scene.camera.size);
  fresh.render(9, settings);
  EXPECT_EQ(reused.readRadiance().pixels, fresh.readRadiance().pixels);
}

}  // namespace
}  // namespace penumbra
