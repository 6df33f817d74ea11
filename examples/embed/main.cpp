// penumbra_embed [SCENE] [--frames N] [--size WxH]: a window of this program's own, with
// Penumbra rendering into its GL context and the picture shown in it. With --frames it closes
// after N frames and prints the picture's mean (for scripts and tests); without, it runs until
// the window is closed, one animation frame per displayed frame.

#include <penumbra/penumbra.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <epoxy/gl.h>

#include <GLFW/glfw3.h>

namespace {

struct Options {
  std::string scene = DEMO_SCENE;
  int frames = 0;  // 0: until the window closes
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

// Renders and shows frames until the window closes or options.frames are shown; prints the last
// picture's mean. The renderer lives inside this call, so its GL objects go while the window's
// context is still there.
void show(GLFWwindow* window, const Options& options) {
  // The in-memory scene API (issue 17, item 3) will let a program build its scene here instead
  // of loading a file.
  penumbra::api::Scene scene = penumbra::api::Scene::load(options.scene);
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
      frame, options.scene.c_str(), image.width, image.height, penumbra::api::version(),
      penumbra::api::currentGlRenderer().c_str(), sum[0] / pixels, sum[1] / pixels,
      sum[2] / pixels);
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
