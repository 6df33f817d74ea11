// penumbra_embed [SCENE] [--frames N] [--size WxH]: a window of this program's own, with
// Penumbra rendering into its GL context and the picture shown in it. The scene is built in
// memory (a box on a floor under a warm panel light), or loaded from SCENE when one is named.
// With --frames it closes after N frames and prints the picture's mean (for scripts and tests);
// without, it runs until the window is closed, one animation frame per displayed frame.

#include <penumbra/penumbra.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include <epoxy/gl.h>

#include <GLFW/glfw3.h>

namespace {

struct Options {
  std::optional<std::string> scene;  // none: the scene built in memory
  int frames = 0;                    // 0: until the window closes
  int width = 256;
  int height = 256;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--frames" && i + 1 < argc) {
      options.frames = std::atoi(argv[++i]);
    } else if (argument == "--size" && i + 1 < argc) {
      if (std::sscanf(argv[++i], "%dx%d", &options.width, &options.height) != 2)
        throw std::runtime_error(std::string("--size ") + argv[i] + ": expected WIDTHxHEIGHT");
    } else {
      options.scene = argument;
    }
  }
  if (options.frames < 0 || options.width <= 0 || options.height <= 0)
    throw std::runtime_error("--frames and --size take positive numbers");
  return options;
}

// The window with a GL 4.5 core context current, which Penumbra renders into.
GLFWwindow* openWindow(const Options& options) {
  if (glfwInit() != GLFW_TRUE)
    throw std::runtime_error("GLFW cannot start (no display?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window =
      glfwCreateWindow(options.width, options.height, "Penumbra in a window", nullptr, nullptr);
  if (window == nullptr)
    throw std::runtime_error("no window with an OpenGL 4.5 core context");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  return window;
}

// A unit cube resting on a 6 x 6 floor, under a square light 2 units up, seen from the front:
// the scene as a program builds it from its own data, with no file.
penumbra::api::Scene buildScene() {
  using penumbra::api::Vec3;
  penumbra::api::SceneDescription description;
  penumbra::api::MaterialDescription panel;
  panel.name = "panel";
  panel.emission = Vec3{6.0f, 5.0f, 4.0f};
  penumbra::api::MaterialDescription clay;
  clay.name = "clay";
  clay.diffuse = {0.7f, 0.45f, 0.35f};
  description.materials = {panel, clay};

  penumbra::api::QuadLightDescription light;
  light.name = "panel";
  light.corners = {Vec3{-0.5f, 2.0f, -0.5f}, Vec3{0.5f, 2.0f, -0.5f}, Vec3{0.5f, 2.0f, 0.5f},
                   Vec3{-0.5f, 2.0f, 0.5f}};
  light.emittingSidePoint = Vec3{0.0f, 0.0f, 0.0f};
  light.material = "panel";
  description.lights = {light};

  penumbra::api::CameraDescription camera;
  camera.position = {0.0f, 2.5f, 5.0f};
  camera.target = {0.0f, 0.3f, 0.0f};
  description.camera = camera;

  penumbra::api::ObjectDescription floor;
  floor.meshName = "floor";
  floor.positions = {Vec3{-3, 0, -3}, Vec3{3, 0, -3}, Vec3{3, 0, 3}, Vec3{-3, 0, 3}};
  floor.triangles = {{0, 3, 2}, {0, 2, 1}};
  penumbra::api::ObjectDescription cube;
  cube.meshName = "cube";
  for (int corner = 0; corner < 8; ++corner)
    cube.positions.push_back(
        Vec3{corner & 1 ? 0.5f : -0.5f, corner & 2 ? 1.0f : 0.0f, corner & 4 ? 0.5f : -0.5f});
  // Two triangles a face, wound counter-clockwise seen from outside.
  cube.triangles = {{0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2},
                    {1, 3, 7}, {1, 7, 5}, {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
  cube.normalsMode = penumbra::api::Normals::Flat;
  cube.material = "clay";
  cube.transform = {{penumbra::api::TransformStep::Kind::Rotate, Vec3{0, 1, 0}, 30.0f}};
  description.objects = {floor, cube};
  return penumbra::api::Scene::build(description);
}

// Renders and shows frames until the window closes or options.frames are shown; prints the last
// picture's mean. The renderer lives inside this call, so its GL objects go while the window's
// context is still there.
void show(GLFWwindow* window, const Options& options) {
  penumbra::api::Scene scene =
      options.scene ? penumbra::api::Scene::load(*options.scene) : buildScene();
  penumbra::api::Renderer renderer(scene, options.width, options.height);
  penumbra::api::Settings settings;
  settings.vplsPerLight = 64;

  // The host's own framebuffer around Penumbra's texture, to copy it to the window.
  GLuint picture = 0;
  glCreateFramebuffers(1, &picture);
  glNamedFramebufferTexture(picture, GL_COLOR_ATTACHMENT0, renderer.texture(), 0);
  // The window shows sRGB; the renderer's radiance is linear.
  glEnable(GL_FRAMEBUFFER_SRGB);

  int frame = 0;
  while (!glfwWindowShouldClose(window) && (options.frames == 0 || frame < options.frames)) {
    renderer.render(frame, settings);
    glBlitNamedFramebuffer(picture, 0, 0, 0, options.width, options.height, 0, 0, options.width,
                           options.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glfwSwapBuffers(window);
    glfwPollEvents();
    ++frame;
  }

  const penumbra::api::Image image = renderer.readImage();
  double sum[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < image.rgba.size(); ++i)
    if (i % 4 < 3)
      sum[i % 4] += image.rgba[i];
  const double pixels = static_cast<double>(image.width) * image.height;
  std::printf(
      "penumbra_embed: %d frames of %s at %dx%d with Penumbra %s on %s; mean radiance "
      "%.4f %.4f %.4f\n",
      frame, options.scene ? options.scene->c_str() : "the scene built in memory", image.width,
      image.height, penumbra::api::version(), penumbra::api::currentGlRenderer().c_str(),
      sum[0] / pixels, sum[1] / pixels, sum[2] / pixels);
  glDeleteFramebuffers(1, &picture);
}

int run(const Options& options) {
  GLFWwindow* window = openWindow(options);
  try {
    show(window, options);
  } catch (...) {
    glfwTerminate();
    throw;
  }
  glfwTerminate();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const penumbra::api::Error& error) {
    std::fprintf(stderr, "penumbra_embed: error: %s\n", error.what());
    return 1;
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "penumbra_embed: error: %s\n", error.what());
    return 1;
  }
}
