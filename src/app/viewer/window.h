#pragma once
// The viewer's window: GLFW with an OpenGL 4.5 core debug context (GLX on X11, which Mesa's
// llvmpipe serves under Xvfb), and Dear ImGui on top of it.

#include <string>
#include <vector>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace penumbra::app {

class Window {
 public:
  // Opens the window, makes its context current, turns GL debug output on and sets up ImGui.
  // Throws gl::ContextError when there is no display or no GL 4.5 core context.
  Window(const std::string& title, glm::ivec2 size);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  // In pixels; 0x0 while the window is minimised.
  glm::ivec2 framebufferSize() const;

  // Starts an ImGui frame (after polling events); drawInterface draws it over the picture and
  // present shows the frame.
  void beginFrame();
  void drawInterface();
  void present();

  // Keys pressed since the last call, in order. A press and its release can both arrive between
  // two slow frames (seconds apart on llvmpipe), where a look at the key's state would miss it.
  std::vector<int> takePressedKeys();
  bool keyDown(int key) const;
  void recordKeyPress(int key) { pressedKeys_.push_back(key); }

 private:
  GLFWwindow* window_ = nullptr;
  std::vector<int> pressedKeys_;
};

}  // namespace penumbra::app
