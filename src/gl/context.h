#pragma once
// A headless OpenGL 4.5 core context through EGL: an EGL device when one exists, otherwise
// Mesa's surfaceless platform (llvmpipe without a GPU). Rendering goes into the project's own
// framebuffers. PENUMBRA_EGL_PLATFORM=device|surfaceless forces one platform.

#include <memory>
#include <stdexcept>
#include <string>

namespace penumbra::gl {

class ContextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ContextInfo {
  std::string vendor;
  std::string renderer;
  std::string version;
  std::string platform;       // "device" or "surfaceless"
  bool timerQueries = false;  // false where GL_TIME_ELAPSED queries return 0 (llvmpipe)
};

// Creates the context, makes it current on the calling thread, loads the GL entry points and
// turns debug output on (see debug.h). Throws ContextError with a clear message when EGL or
// GL 4.5 core is missing.
class HeadlessContext {
 public:
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  const ContextInfo& info() const { return info_; }

 private:
  struct EglState;
  std::unique_ptr<EglState> egl_;
  ContextInfo info_;
};

// Fills the GL strings and whether timer queries work, for the current context.
ContextInfo queryContextInfo(const std::string& platform);

}  // namespace penumbra::gl
