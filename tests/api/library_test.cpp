// The library's facade (include/penumbra/) in a host's GL context: what it renders, and that it
// gives the host its GL state back (docs/library.md, "GL state").

#include <penumbra/penumbra.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/handles.h"
#include "render/frame.h"
#include "render/gl_state.h"
#include "test_files.h"

namespace penumbra {
namespace {

constexpr int kSize = 64;

std::filesystem::path shadowBox() {
  return test::sourceDirectory() / "scenes/shadow_box.scene";
}

// A host's state that differs from GL's initial one in everything GlState captures, with
// objects of its own bound where the renderer binds its objects, and switches that would spoil
// the renderer's draws, copies and read-backs if it kept them.
struct HostState {
  GlState initial = GlState::capture();  // put back when the test ends
  gl::Texture colour{GL_TEXTURE_2D};
  gl::Texture volume{GL_TEXTURE_3D};
  gl::Framebuffer framebuffer;
  gl::Buffer buffer;
  gl::VertexArray vertexArray;
  gl::Sampler sampler;
  GLuint program = linkedProgram();

  static GLuint linkedProgram() {
    const char* source = "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    return glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &source);
  }

  HostState() {
    glTextureStorage2D(colour.id(), 1, GL_RGBA8, 16, 16);
    glTextureStorage3D(volume.id(), 1, GL_R32UI, 4, 4, 4);
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
    glNamedBufferStorage(buffer.id(), 1024, nullptr, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(3, 5, 11, 7);
    glScissor(1, 2, 3, 4);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_BLEND);
    glEnable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    for (GLenum capability : {GL_RASTERIZER_DISCARD, GL_POLYGON_OFFSET_FILL, GL_COLOR_LOGIC_OP,
                              GL_FRAMEBUFFER_SRGB, GL_PRIMITIVE_RESTART, GL_CLIP_DISTANCE3})
      glEnable(capability);
    glDisable(GL_MULTISAMPLE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glUseProgram(program);
    glBindVertexArray(vertexArray.id());
    // Every binding point and unit the renderer's shaders use (0 to 14), and a range.
    for (GLuint index = 0; index < 16; ++index) {
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, index, buffer.id(), 256, 512);
      glBindBufferBase(GL_UNIFORM_BUFFER, index % 8, buffer.id());
    }
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, buffer.id());
    for (GLenum target : {GL_ARRAY_BUFFER, GL_DISPATCH_INDIRECT_BUFFER, GL_DRAW_INDIRECT_BUFFER,
                          GL_PIXEL_PACK_BUFFER, GL_PIXEL_UNPACK_BUFFER})
      glBindBuffer(target, buffer.id());
    for (GLuint unit = 0; unit < 8; ++unit) {
      glBindTextureUnit(unit, unit % 2 == 0 ? colour.id() : volume.id());
      glBindSampler(unit, sampler.id());
      glBindImageTexture(unit, volume.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    }
    glActiveTexture(GL_TEXTURE5);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  }
  ~HostState() {
    initial.restore();
    glDeleteProgram(program);
  }
  HostState(const HostState&) = delete;
  HostState& operator=(const HostState&) = delete;
};

api::Settings everyPass() {
  api::Settings settings;
  settings.vplsPerLight = 16;
  settings.indirect = true;
  return settings;
}

// The renderer's passes alone do change the context's state, so a capture that sees no change
// after the facade rendered means the guard put it back. It starts from GL's initial state with a
// viewport no pass sets: an earlier test in the same process may have left the renderer's own
// viewport, program or bindings behind, which made this test fail when run after it.
TEST(LibraryGlState, TheRendererAloneChangesTheState) {
  Scene scene = loadScene(parseSceneFile(shadowBox()));
  glViewport(1, 2, 3, 4);
  GlState::initial(GlState::capture()).restore();
  const GlState before = GlState::capture();
  Renderer renderer(scene, {kSize, kSize});
  RenderSettings settings;
  settings.vplsPerLight = 16;
  settings.indirect.enabled = true;
  renderer.render(0, settings);
  const GlState after = GlState::capture();
  EXPECT_NE(after.viewport, before.viewport);
  EXPECT_NE(after.program, before.program);
  EXPECT_NE(after.storageBuffers, before.storageBuffers);
  EXPECT_NE(after.textureUnits, before.textureUnits);
  EXPECT_NE(after.imageUnits, before.imageUnits);
  GlState::initial(before).restore();
}

// Under the host's state, the facade renders what it renders from GL's initial state, and the
// host has its state back after each call.
TEST(LibraryGlState, RenderingGivesTheHostItsStateBack) {
  api::Scene scene = api::Scene::load(shadowBox());
  api::Settings naive = everyPass();
  naive.mode = api::Mode::Naive;
  std::vector<api::Image> expected;
  {
    api::Renderer clean(scene, kSize, kSize);
    for (const api::Settings& settings : {everyPass(), naive}) {
      clean.render(0, settings);
      expected.push_back(clean.readImage());
    }
  }

  const HostState host;
  const GlState before = GlState::capture();
  api::Renderer renderer(scene, kSize, kSize);
  EXPECT_EQ(GlState::capture(), before) << "after the renderer was made";
  renderer.render(0, everyPass());
  EXPECT_EQ(GlState::capture(), before) << "after a frame";
  EXPECT_EQ(renderer.readImage().rgba, expected[0].rgba);
  EXPECT_EQ(GlState::capture(), before) << "after the read-back";
  renderer.render(0, naive);
  EXPECT_EQ(GlState::capture(), before) << "after a naive frame";
  EXPECT_EQ(renderer.readImage().rgba, expected[1].rgba);
}

// A host that deletes its program while it is current: GL keeps it current until another is
// used, so the guard cannot give it back once the renderer used its own; the host is left with
// no program and no GL error (restoring the freed name was GL_INVALID_VALUE).
TEST(LibraryGlState, AProgramTheHostDeletedIsNotGivenBack) {
  api::Scene scene = api::Scene::load(shadowBox());
  const GLuint hostProgram = glCreateProgram();
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* source = "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  glAttachShader(hostProgram, shader);
  glLinkProgram(hostProgram);
  glDeleteShader(shader);
  glUseProgram(hostProgram);
  glDeleteProgram(hostProgram);
  api::Renderer renderer(scene, kSize, kSize);
  renderer.render(0, everyPass());
  GLint current = -1;
  glGetIntegerv(GL_CURRENT_PROGRAM, &current);
  EXPECT_EQ(current, 0);
}

TEST(LibraryGlState, AFailedFrameGivesTheStateBackToo) {
  const HostState host;
  const GlState before = GlState::capture();
  api::Scene scene = api::Scene::load(shadowBox());
  api::Renderer renderer(scene, kSize, kSize);
  api::Settings wrong;
  wrong.vplsPerLight = 15;  // not a square
  try {
    renderer.render(0, wrong);
    ADD_FAILURE() << "expected an Error";
  } catch (const api::Error& error) {
    EXPECT_EQ(error.kind(), api::Error::Kind::BadInput);
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "15", error.what());
  }
  EXPECT_EQ(GlState::capture(), before);
}

// The facade's defaults and its conversion give the renderer's own picture, and its texture
// holds the picture readImage returns (GL's bottom row first).
TEST(Library, RendersWhatTheRendererRenders) {
  Scene internalScene = loadScene(parseSceneFile(shadowBox()));
  Renderer internal(internalScene, {kSize, kSize});
  internal.render(2, RenderSettings{});
  const Image expected = internal.readRadiance();

  api::Scene scene = api::Scene::load(shadowBox());
  api::Renderer renderer(scene, kSize, kSize);
  renderer.render(2);
  const api::Image image = renderer.readImage();
  ASSERT_EQ(image.width, kSize);
  ASSERT_EQ(image.height, kSize);
  ASSERT_EQ(image.rgba.size(), expected.pixels.size() * 4);
  EXPECT_TRUE(std::equal(image.rgba.begin(), image.rgba.end(), &expected.pixels[0].x));

  const Image texture = readTexture(renderer.texture(), {kSize, kSize}, RowOrder::TopFirst);
  EXPECT_TRUE(std::equal(image.rgba.begin(), image.rgba.end(), &texture.pixels[0].x));
}

// The shadow box through the library with a switch of its settings turned from its default to
// `switched` renders what the renderer renders with `internalSettings`, bit for bit, and with the
// switch at its default differently.
void expectSwitchRendersWhatTheRendererRenders(bool api::Settings::*option, bool switched,
                                               const RenderSettings& internalSettings) {
  Scene internalScene = loadScene(parseSceneFile(shadowBox()));
  Renderer internal(internalScene, {kSize, kSize});
  internal.render(0, internalSettings);
  const Image expected = internal.readRadiance();

  api::Scene scene = api::Scene::load(shadowBox());
  api::Renderer renderer(scene, kSize, kSize);
  api::Settings settings;
  EXPECT_NE(settings.*option, switched);
  settings.vplsPerLight = internalSettings.vplsPerLight;
  settings.*option = switched;
  renderer.render(0, settings);
  const api::Image image = renderer.readImage();
  ASSERT_EQ(image.rgba.size(), expected.pixels.size() * 4);
  EXPECT_TRUE(std::equal(image.rgba.begin(), image.rgba.end(), &expected.pixels[0].x));
  settings.*option = !switched;
  renderer.render(0, settings);
  EXPECT_NE(renderer.readImage().rgba, image.rgba);
}

// exactVisibility chooses the renderer's BVH shadow rays, which shadow the box differently from
// the voxels.
TEST(Library, ExactVisibilityRendersWhatTheBvhRenders) {
  RenderSettings exact;
  exact.vplsPerLight = 16;
  exact.shadows.visibility = ShadowSettings::Visibility::Bvh;
  expectSwitchRendersWhatTheRendererRenders(&api::Settings::exactVisibility, true, exact);
}

// cubicVoxels off chooses the renderer's equal voxel grid, whose voxels shadow the box differently
// from the default cubic grid's.
TEST(Library, EqualVoxelsRenderWhatTheEqualGridRenders) {
  RenderSettings equal;
  equal.vplsPerLight = 16;
  equal.shadows.voxels.shape = VoxelSettings::Shape::Equal;
  expectSwitchRendersWhatTheRendererRenders(&api::Settings::cubicVoxels, false, equal);
}

TEST(Library, ErrorsHaveTheirKindAndTheParsersMessage) {
  const auto directory = test::scratchDirectory();
  const auto file = test::writeFile(directory, "bad.scene", "material m\n  dif 1 x 1\nend\n");
  try {
    api::Scene::load(file);
    ADD_FAILURE() << "expected an Error";
  } catch (const api::Error& error) {
    EXPECT_EQ(error.kind(), api::Error::Kind::BadInput);
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "bad.scene:2:", error.what());
  }
  // Alpha 1: EXR files store RGB, and a read-back alpha is 1.
  const api::Image image{2, 1, {0.5f, 0.25f, 0.125f, 1.0f, 1.0f, 2.0f, 3.0f, 1.0f}};
  EXPECT_THROW(api::saveImage(image, directory / "missing" / "a.exr"), api::Error);
  api::saveImage(image, directory / "a.exr");
  const api::Image loaded = api::loadImage(directory / "a.exr");
  EXPECT_EQ(loaded.width, 2);
  EXPECT_EQ(loaded.rgba, image.rgba);
}

// A floor, a box resting on it with a texture from memory, and a light: the facade's
// description and the same scene as a file render bit-identically.
TEST(Library, ASceneBuiltInMemoryRendersAsItsFile) {
  const auto directory = test::scratchDirectory();
  const api::Image checker{2,
                           2,
                           {1.0f, 0.2f, 0.2f, 1.0f, 0.2f, 1.0f, 0.2f, 1.0f,  //
                            0.2f, 0.2f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f}};
  api::saveImage(checker, directory / "checker.exr");
  test::writeFile(directory, "floor.obj",
                  "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                  "f 1/1 4/4 3/3\nf 1/1 3/3 2/2\n");
  const auto file = test::writeFile(directory, "scene.scene", R"(
material glow
  emit 4 3 2
end
material painted
  dif 0.9 0.9 0.9
  tex checker.exr
end
area_light panel
  pos1 -0.5 2 -0.5
  pos2 0.5 2 -0.5
  pos3 0.5 2 0.5
  pos4 -0.5 2 0.5
  at 0 0 0
  mat glow
end
camera front
  pos 0 2.5 5
  at 0 0.3 0
  screen_size 32 32
end
object floor.obj
  rotate 30 0 1 0
  translate 0.5 0 0
  mat painted
end
)");
  api::Scene fromFile = api::Scene::load(file);

  using api::Vec3;
  api::SceneDescription description;
  api::MaterialDescription glow;
  glow.name = "glow";
  glow.emission = Vec3{4.0f, 3.0f, 2.0f};
  api::MaterialDescription painted;
  painted.name = "painted";
  painted.diffuse = {0.9f, 0.9f, 0.9f};
  painted.textureImage = api::loadImage(directory / "checker.exr");
  description.materials = {glow, painted};
  api::QuadLightDescription panel;
  panel.name = "panel";
  panel.corners = {Vec3{-0.5f, 2, -0.5f}, Vec3{0.5f, 2, -0.5f}, Vec3{0.5f, 2, 0.5f},
                   Vec3{-0.5f, 2, 0.5f}};
  panel.emittingSidePoint = Vec3{0, 0, 0};
  panel.material = "glow";
  description.lights = {panel};
  api::CameraDescription camera;
  camera.name = "front";
  camera.position = {0, 2.5f, 5};
  camera.target = {0, 0.3f, 0};
  camera.width = 32;
  camera.height = 32;
  description.camera = camera;
  api::ObjectDescription floor;
  floor.meshName = "floor";
  floor.positions = {Vec3{-3, 0, -3}, Vec3{3, 0, -3}, Vec3{3, 0, 3}, Vec3{-3, 0, 3}};
  floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  floor.triangles = {{0, 3, 2}, {0, 2, 1}};
  floor.transform = {{api::TransformStep::Kind::Rotate, Vec3{0, 1, 0}, 30.0f},
                     {api::TransformStep::Kind::Translate, Vec3{0.5f, 0, 0}, 0.0f}};
  floor.material = "painted";
  description.objects = {floor};
  api::Scene built = api::Scene::build(description);

  ASSERT_EQ(built.width(), 32);
  api::Renderer fileRenderer(fromFile, 32, 32);
  fileRenderer.render(0);
  api::Renderer builtRenderer(built, 32, 32);
  builtRenderer.render(0);
  const api::Image expected = fileRenderer.readImage();
  const api::Image image = builtRenderer.readImage();
  EXPECT_EQ(image.rgba, expected.rgba);
  // The picture shows the lit, textured floor (a black one would also be equal).
  EXPECT_GT(*std::max_element(image.rgba.begin(), image.rgba.end()), 0.1f);
}

// A value the parser refuses is refused in memory with the parser's words, as BadInput.
TEST(Library, ASceneBuiltInMemoryIsCheckedAsAFileIs) {
  api::SceneDescription description;
  api::MaterialDescription bright;
  bright.name = "bright";
  bright.diffuse = {1.5f, 0.5f, 0.5f};
  description.materials = {bright};
  try {
    api::Scene::build(description);
    ADD_FAILURE() << "expected an Error";
  } catch (const api::Error& error) {
    EXPECT_EQ(error.kind(), api::Error::Kind::BadInput);
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "in-memory scene", error.what());
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, "'dif' values must be in [0, 1]", error.what());
  }
  api::ObjectDescription broken;
  broken.positions = {{0, 0, 0}, {1, 0, 0}, {0, std::nanf(""), 1}};
  broken.triangles = {{0, 1, 2}};
  description.materials.clear();
  description.objects = {broken};
  EXPECT_THROW(api::Scene::build(description), api::Error);
}

TEST(Library, VersionIsTheProjects) {
  EXPECT_STREQ(api::version(), PENUMBRA_VERSION_STRING);
  EXPECT_FALSE(api::currentGlRenderer().empty());
}

}  // namespace
}  // namespace penumbra
