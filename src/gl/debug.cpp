#include "gl/debug.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <epoxy/gl.h>

namespace penumbra::gl {

namespace {

// Atomic because a driver may still call back from its own threads if a context is not
// synchronous.
std::atomic<std::size_t> glErrors{0};

const char* typeName(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR:
      return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR:
      return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR:
      return "undefined-behavior";
    case GL_DEBUG_TYPE_PORTABILITY:
      return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE:
      return "performance";
    case GL_DEBUG_TYPE_MARKER:
      return "marker";
    case GL_DEBUG_TYPE_PUSH_GROUP:
      return "push-group";
    case GL_DEBUG_TYPE_POP_GROUP:
      return "pop-group";
    default:
      return "other";
  }
}

const char* severityName(GLenum severity) {
  switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH:
      return "high";
    case GL_DEBUG_SEVERITY_MEDIUM:
      return "medium";
    case GL_DEBUG_SEVERITY_LOW:
      return "low";
    default:
      return "notification";
  }
}

const char* errorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST:
      return "GL_CONTEXT_LOST";
    default:
      return "an unknown GL error";
  }
}

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint /*id*/, GLenum severity,
                               GLsizei length, const GLchar* message, const void* /*user*/) {
  // A failed compile is not a GL error: Program throws ShaderError with the same log.
  if (type == GL_DEBUG_TYPE_ERROR && source != GL_DEBUG_SOURCE_SHADER_COMPILER)
    ++glErrors;
  std::fprintf(stderr, "GL %s %s: %.*s\n", typeName(type), severityName(severity),
               static_cast<int>(length), message);
}

}  // namespace

void enableDebugOutput() {
  glEnable(GL_DEBUG_OUTPUT);
  // Synchronous, so that a message arrives inside the call that caused it (and its test).
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr,
                        GL_FALSE);
  const char* provoke = std::getenv("PENUMBRA_TEST_GL_ERROR");
  if (provoke != nullptr && std::strcmp(provoke, "1") == 0) {
    // GL_INVALID_OPERATION: a core context binds only names from glGenBuffers/glCreateBuffers.
    constexpr GLuint kNeverGenerated = 0x7fffffff;
    glBindBuffer(GL_ARRAY_BUFFER, kNeverGenerated);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
}

std::size_t errorCount() {
  return glErrors;
}

void resetErrorCount() {
  glErrors = 0;
}

void drainErrors() {
  for (GLenum error = glGetError(); error != GL_NO_ERROR; error = glGetError()) {
    ++glErrors;
    std::fprintf(stderr, "GL error: glGetError returned %s\n", errorName(error));
    // A lost context may keep returning GL_CONTEXT_LOST forever.
    if (error == GL_CONTEXT_LOST)
      break;
  }
}

}  // namespace penumbra::gl
