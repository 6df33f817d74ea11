#pragma once
// The one colouring of the debug views (debug_view_colour.glsl) on the C++ side: the uniforms and
// bindings a program that includes it needs, for the viewer's display program, and the compute
// pass that colours a view into a picture for `render --debug-view`.

#include "gl/handles.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/debug_view_registry.h"

namespace penumbra {

// Entries of the colour-map table: enough that its linear interpolation matches the map.
inline constexpr int kColourMapTableSize = 256;

class DebugViewColouring {
 public:
  // Compiles debug_view.comp and fills the colour-map table; throws gl::ShaderError.
  DebugViewColouring();

  // Binds the view's texture to unit 0 (float) or 1 (unsigned), the colour-map table to unit 2,
  // and sets `program`'s colouring uniforms. The binding stays for the caller's draw or
  // dispatch; release() undoes it.
  void prepare(const gl::Program& program, const DebugViewSource& view, float exposureScale) const;
  void release() const;

  // The view coloured texel for texel (exposure 1), row 0 at the top.
  Image colour(const DebugViewSource& view) const;

 private:
  gl::Program program_;
  gl::Texture colourMapTable_{GL_TEXTURE_1D};
  gl::Sampler nearest_;
};

}  // namespace penumbra
