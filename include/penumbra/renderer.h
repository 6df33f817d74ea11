#pragma once
// The GPU renderer in the calling thread's current OpenGL 4.5 core context: the host's window
// context, or a HeadlessContext. Every call needs that same context current.
//
// GL state: the constructor, render() and readImage() work from GL's initial state and put the
// host's state back before they return, exceptions included (docs/library.md, "GL state", lists
// it all: framebuffers, viewport, switches, masks, program, vertex array, buffer bindings, the
// first 32 texture and image units, pixel alignments). What stays is the renderer's own objects
// (textures, buffers, programs, queries), which it deletes when destroyed.

#include <cstdint>
#include <memory>
#include <string>

#include "penumbra/image.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"

namespace penumbra::api {

// A headless GL 4.5 core context through EGL (a GPU's EGL device, or Mesa's llvmpipe without
// one), current on the calling thread while it lives. Throws Error (Gpu).
class HeadlessContext {
 public:
  HeadlessContext();
  // Movable, so that a program can keep it in a member or return it from a function.
  HeadlessContext(HeadlessContext&&) noexcept;
  HeadlessContext& operator=(HeadlessContext&&) noexcept;
  ~HeadlessContext();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// GL_RENDERER of the current context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string currentGlRenderer();

class Renderer {
 public:
  // `scene` must outlive the renderer. Throws Error (Gpu) when a shader fails or the size is
  // beyond the GL implementation's limits.
  Renderer(Scene& scene, int width, int height);
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  ~Renderer();

  // Renders frame `frame`: the animation and the videos at time frame / 30 s, so the same
  // frame index always gives the same picture. Throws Error (BadInput) for settings out of range.
  void render(int frame, const Settings& settings = {});

  // The last frame's linear radiance: a GL_TEXTURE_2D of format GL_RGBA32F, width x height,
  // row 0 at the bottom as GL draws it. It belongs to the renderer, which overwrites it each
  // frame; sample or copy it, do not delete it.
  std::uint32_t texture() const;
  // The same picture read back into CPU memory (row 0 at the top).
  Image readImage() const;

  int width() const;
  int height() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace penumbra::api
