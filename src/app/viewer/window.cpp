#include "app/viewer/window.h"

#include <utility>

#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "gl/context.h"
#include "gl/debug.h"

namespace penumbra::app {
namespace {

// GLFW reports failures through a callback; the last message explains a failed call.
std::string lastGlfwError;

extern "C" void recordGlfwError(int code, const char* description) {
  lastGlfwError = std::string(description) + " (GLFW error " + std::to_string(code) + ")";
}

extern "C" void recordKey(GLFWwindow* window, int key, int, int action, int) {
  if (action == GLFW_PRESS)
    static_cast<Window*>(glfwGetWindowUserPointer(window))->recordKeyPress(key);
}

}  // namespace

Window::Window(const std::string& title, glm::ivec2 size) {
  glfwSetErrorCallback(recordGlfwError);
  if (glfwInit() != GLFW_TRUE) {
    throw gl::ContextError("cannot open a window: " + lastGlfwError +
                           "; the viewer needs a display (set DISPLAY, or run it under xvfb-run)");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  window_ = glfwCreateWindow(size.x, size.y, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string reason = lastGlfwError;
    glfwTerminate();
    throw gl::ContextError("cannot create a window with an OpenGL 4.5 core context: " + reason);
  }
  glfwMakeContextCurrent(window_);
  // The wait for the display's refresh keeps an idle viewer from spinning a core.
  glfwSwapInterval(1);
  gl::enableDebugOutput();
  glfwSetWindowUserPointer(window_, this);
  // Before ImGui's backend, which calls the callback it finds after its own.
  glfwSetKeyCallback(window_, recordKey);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written into the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
}

Window::~Window() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool Window::shouldClose() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

glm::ivec2 Window::framebufferSize() const {
  glm::ivec2 size(0);
  glfwGetFramebufferSize(window_, &size.x, &size.y);
  return size;
}

void Window::beginFrame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Window::drawInterface() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Window::present() {
  glfwSwapBuffers(window_);
}

std::vector<int> Window::takePressedKeys() {
  return std::exchange(pressedKeys_, {});
}

bool Window::keyDown(int key) const {
  return glfwGetKey(window_, key) == GLFW_PRESS;
}

}  // namespace penumbra::app
