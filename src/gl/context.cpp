#include "gl/context.h"

#include <cstdlib>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "gl/debug.h"
#include "gl/handles.h"

namespace penumbra::gl {

namespace {

constexpr const char* kInstallHint =
    "Mesa's llvmpipe provides OpenGL 4.5 core without a GPU: install libegl-mesa0 and "
    "libgl1-mesa-dri.";

const char* eglErrorName(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
      return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
      return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
      return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT:
      return "EGL_BAD_DEVICE_EXT";
    default:
      return "an unknown EGL error";
  }
}

// Reads eglGetError() at once, before any other EGL call can overwrite it.
[[noreturn]] void throwEglFailure(std::string_view platform, std::string_view call) {
  const EGLint error = eglGetError();
  throw ContextError("EGL (" + std::string(platform) + "): " + std::string(call) + " failed with " +
                     eglErrorName(error));
}

bool hasExtension(const char* extensionList, std::string_view wanted) {
  if (extensionList == nullptr)
    return false;
  std::string_view remaining(extensionList);
  while (!remaining.empty()) {
    const auto end = remaining.find(' ');
    if (remaining.substr(0, end) == wanted)
      return true;
    if (end == std::string_view::npos)
      break;
    remaining.remove_prefix(end + 1);
  }
  return false;
}

bool hasClientExtension(std::string_view wanted) {
  // Without client extensions (EGL 1.4 and older) this query fails with EGL_BAD_DISPLAY; clear
  // that error so that it is not reported for a later call.
  const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (extensions == nullptr)
    eglGetError();
  return hasExtension(extensions, wanted);
}

enum class PlatformChoice { automatic, device, surfaceless };

PlatformChoice platformFromEnvironment() {
  const char* value = std::getenv("PENUMBRA_EGL_PLATFORM");
  if (value == nullptr || *value == '\0')
    return PlatformChoice::automatic;
  if (std::strcmp(value, "device") == 0)
    return PlatformChoice::device;
  if (std::strcmp(value, "surfaceless") == 0)
    return PlatformChoice::surfaceless;
  throw ContextError(
      std::string("PENUMBRA_EGL_PLATFORM is \"") + value +
      "\"; expected \"device\" or \"surfaceless\" (or unset to choose automatically)");
}

std::string glString(GLenum name) {
  const auto* value = reinterpret_cast<const char*>(glGetString(name));
  return value != nullptr ? value : "";
}

// Throws unless the current context is OpenGL 4.5 or newer with the core profile.
void requireGl45Core() {
  GLint major = 0;
  GLint minor = 0;
  GLint profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  const bool recentEnough = major > 4 || (major == 4 && minor >= 5);
  const bool core = (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
  if (recentEnough && core)
    return;
  throw ContextError("OpenGL 4.5 core profile is needed, but the driver created \"" +
                     glString(GL_VERSION) + "\" (" + (core ? "core" : "not core") +
                     " profile) on \"" + glString(GL_RENDERER) + "\". " + kInstallHint);
}

// Owns an EGL display and the context created on it; releases both when destroyed.
class EglSession {
 public:
  EglSession() = default;
  EglSession(const EglSession&) = delete;
  EglSession& operator=(const EglSession&) = delete;
  EglSession(EglSession&& other) noexcept
      : display(std::exchange(other.display, EGL_NO_DISPLAY)),
        context(std::exchange(other.context, EGL_NO_CONTEXT)),
        platform(std::move(other.platform)) {}
  EglSession& operator=(EglSession&&) = delete;
  ~EglSession() {
    if (display == EGL_NO_DISPLAY)
      return;
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context)
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    eglTerminate(display);
    eglReleaseThread();
  }

  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string platform;
};

// Initializes `display`, creates a 4.5 core debug context on it and makes it current. `session`
// owns the display from the start, so a failure part way releases what was created.
void createContext(EglSession& session, EGLDisplay display, std::string_view platform) {
  if (display == EGL_NO_DISPLAY)
    throwEglFailure(platform, "eglGetPlatformDisplayEXT");
  session.display = display;
  session.platform = platform;

  EGLint eglMajor = 0;
  EGLint eglMinor = 0;
  if (eglInitialize(display, &eglMajor, &eglMinor) != EGL_TRUE)
    throwEglFailure(platform, "eglInitialize");
  // The context attributes below (EGL_CONTEXT_MAJOR_VERSION, EGL_CONTEXT_OPENGL_DEBUG) are
  // core in EGL 1.5.
  if (eglMajor < 1 || (eglMajor == 1 && eglMinor < 5)) {
    throw ContextError("EGL (" + std::string(platform) + "): EGL 1.5 is needed, found " +
                       std::to_string(eglMajor) + "." + std::to_string(eglMinor) + ". " +
                       kInstallHint);
  }
  if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
    throw ContextError("EGL (" + std::string(platform) +
                       "): the display lacks EGL_KHR_surfaceless_context. " + kInstallHint);
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE)
    throwEglFailure(platform, "eglBindAPI");

  // No surface is ever created, so any surface type will do.
  const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                     EGL_DONT_CARE, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  if (eglChooseConfig(display, configAttributes, &config, 1, &configCount) != EGL_TRUE)
    throwEglFailure(platform, "eglChooseConfig");
  if (configCount == 0) {
    throw ContextError("EGL (" + std::string(platform) +
                       "): eglChooseConfig found no config that renders desktop OpenGL. " +
                       kInstallHint);
  }

  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_CONTEXT_OPENGL_DEBUG,
                                      EGL_TRUE,
                                      EGL_NONE};
  session.context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
  if (session.context == EGL_NO_CONTEXT) {
    const EGLint error = eglGetError();
    throw ContextError("EGL (" + std::string(platform) +
                       "): eglCreateContext for OpenGL 4.5 core failed with " +
                       eglErrorName(error) + ". " + kInstallHint);
  }
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, session.context) != EGL_TRUE)
    throwEglFailure(platform, "eglMakeCurrent");
}

std::vector<EGLDeviceEXT> queryDevices() {
  constexpr std::string_view platform = "device";
  if (!hasClientExtension("EGL_EXT_device_enumeration") ||
      !hasClientExtension("EGL_EXT_platform_device")) {
    throw ContextError(
        "EGL (device): the EGL library lacks EGL_EXT_device_enumeration or "
        "EGL_EXT_platform_device");
  }
  EGLint count = 0;
  if (eglQueryDevicesEXT(0, nullptr, &count) != EGL_TRUE)
    throwEglFailure(platform, "eglQueryDevicesEXT");
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count) != EGL_TRUE)
    throwEglFailure(platform, "eglQueryDevicesEXT");
  devices.resize(static_cast<std::size_t>(count));
  if (devices.empty())
    throw ContextError("EGL (device): eglQueryDevicesEXT found no device");
  return devices;
}

bool isSoftwareDevice(EGLDeviceEXT device) {
  return hasExtension(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

// Tries each device in turn. Mesa's software device is skipped unless `includeSoftware`, since
// automatic selection reaches the same llvmpipe through the surfaceless platform.
EglSession createOnDevice(bool includeSoftware) {
  std::string failures;
  for (EGLDeviceEXT device : queryDevices()) {
    if (!includeSoftware && isSoftwareDevice(device))
      continue;
    EglSession session;
    try {
      createContext(session, eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr),
                    "device");
      requireGl45Core();
      return session;
    } catch (const ContextError& error) {
      failures += std::string(failures.empty() ? "" : "; ") + error.what();
    }
  }
  throw ContextError(failures.empty() ? "EGL (device): no hardware EGL device" : failures);
}

EglSession createSurfaceless() {
  if (!hasClientExtension("EGL_MESA_platform_surfaceless")) {
    throw ContextError("EGL (surfaceless): the EGL library lacks EGL_MESA_platform_surfaceless. " +
                       std::string(kInstallHint));
  }
  EglSession session;
  createContext(
      session,
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
      "surfaceless");
  requireGl45Core();
  return session;
}

EglSession createAutomatic() {
  std::string deviceFailure;
  try {
    return createOnDevice(false);
  } catch (const ContextError& error) {
    deviceFailure = error.what();
  }
  try {
    return createSurfaceless();
  } catch (const ContextError& error) {
    throw ContextError(std::string(error.what()) + " (before that, " + deviceFailure + ")");
  }
}

}  // namespace

struct HeadlessContext::EglState {
  EglSession session;
};

namespace {

EglSession createSession() {
  const PlatformChoice choice = platformFromEnvironment();
  if (choice == PlatformChoice::device)
    return createOnDevice(true);
  if (choice == PlatformChoice::surfaceless)
    return createSurfaceless();
  return createAutomatic();
}

}  // namespace

HeadlessContext::HeadlessContext() : egl_(std::make_unique<EglState>(EglState{createSession()})) {
  enableDebugOutput();
  info_ = queryContextInfo(egl_->session.platform);
}

HeadlessContext::~HeadlessContext() = default;

namespace {

// GPU time of `clears` clears of a `size` x `size` texture, by a GL_TIME_ELAPSED query.
GLuint64 timeTextureClears(GLsizei size, int clears) {
  Texture texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.id(), 1, GL_RGBA8, size, size);
  Query query(GL_TIME_ELAPSED);
  const GLubyte color[4] = {10, 20, 30, 40};
  glBeginQuery(GL_TIME_ELAPSED, query.id());
  for (int clear = 0; clear < clears; ++clear)
    glClearTexImage(texture.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, color);
  glEndQuery(GL_TIME_ELAPSED);
  GLuint64 nanoseconds = 0;
  glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &nanoseconds);
  return nanoseconds;
}

// A non-zero answer is not enough: llvmpipe (Mesa 22) answers 1 ns for any amount of clearing
// or compute work. Working timers see 64 MiB of clears take longer than one tiny clear.
bool timerQueriesWork() {
  const GLuint64 tiny = timeTextureClears(16, 1);
  const GLuint64 large = timeTextureClears(1024, 16);
  return large > tiny;
}

}  // namespace

ContextInfo queryContextInfo(const std::string& platform) {
  ContextInfo info;
  info.vendor = glString(GL_VENDOR);
  info.renderer = glString(GL_RENDERER);
  info.version = glString(GL_VERSION);
  info.platform = platform;
  info.timerQueries = timerQueriesWork();
  return info;
}

}  // namespace penumbra::gl
