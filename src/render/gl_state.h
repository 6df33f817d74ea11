#pragma once
// The GL state that a frame of the renderer changes, or that would change what it renders,
// captured from the current context, so that Penumbra can render into a host application's
// context from GL's initial state and then give the host its own state back (docs/library.md,
// "GL state"). Objects the renderer creates and deletes are its own; what is captured here are
// the host's bindings and switches.

#include <array>
#include <vector>

#include <epoxy/gl.h>

namespace penumbra {

// Indexed binding points and units beyond this many are neither captured nor touched by the
// renderer (its shaders use binding points 0 to 14 and texture and image units 0 to 7).
inline constexpr GLuint kCapturedBindingPoints = 32;

struct GlState {
  struct BufferRange {
    GLint buffer = 0;
    GLint64 start = 0;
    GLint64 size = 0;
    bool operator==(const BufferRange&) const = default;
  };
  struct TextureUnit {
    // GL_TEXTURE_2D, _2D_ARRAY, _3D, _CUBE_MAP and _BUFFER bindings, then the sampler.
    std::array<GLint, 5> textures{};
    GLint sampler = 0;
    bool operator==(const TextureUnit&) const = default;
  };
  struct ImageUnit {
    GLint texture = 0;
    GLint level = 0;
    GLboolean layered = GL_FALSE;
    GLint layer = 0;
    GLint access = GL_READ_ONLY;
    GLint format = GL_R8;
    bool operator==(const ImageUnit&) const = default;
  };

  GLint drawFramebuffer = 0;
  GLint readFramebuffer = 0;
  std::array<GLint, 4> viewport{};
  std::array<GLint, 4> scissorBox{};
  // glIsEnabled of each of kCapabilities (gl_state.cpp), in its order.
  std::vector<GLboolean> capabilities;
  GLint depthFunc = GL_LESS;
  GLboolean depthMask = GL_TRUE;
  std::array<GLboolean, 4> colorMask{GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  GLint polygonMode = GL_FILL;
  GLint clipOrigin = GL_LOWER_LEFT;
  GLint clipDepthMode = GL_NEGATIVE_ONE_TO_ONE;
  GLint program = 0;
  GLint vertexArray = 0;
  // GL_ARRAY_BUFFER, GL_DISPATCH_INDIRECT_BUFFER, GL_DRAW_INDIRECT_BUFFER, GL_PIXEL_PACK_BUFFER,
  // GL_PIXEL_UNPACK_BUFFER, GL_SHADER_STORAGE_BUFFER, GL_UNIFORM_BUFFER,
  // GL_ATOMIC_COUNTER_BUFFER: the generic binding points.
  std::array<GLint, 8> buffers{};
  std::vector<BufferRange> storageBuffers;
  std::vector<BufferRange> uniformBuffers;
  std::vector<BufferRange> atomicCounterBuffers;
  GLint activeTexture = GL_TEXTURE0;
  std::vector<TextureUnit> textureUnits;
  std::vector<ImageUnit> imageUnits;
  GLint packAlignment = 4;
  GLint unpackAlignment = 4;

  bool operator==(const GlState&) const = default;

  // Reads the state of the current context.
  static GlState capture();
  // GL's initial values, with as many indexed bindings and units as `captured` and its viewport
  // and scissor box (which the renderer's passes set where they matter).
  static GlState initial(const GlState& captured);
  // Makes it the current context's state again.
  void restore() const;
};

// Captures the state and sets GL's initial one when made, and restores the captured state when
// it goes, exceptions included.
class GlStateGuard {
 public:
  GlStateGuard() : saved_(GlState::capture()) { GlState::initial(saved_).restore(); }
  ~GlStateGuard() { saved_.restore(); }
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

 private:
  GlState saved_;
};

}  // namespace penumbra
