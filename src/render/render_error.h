#pragma once

#include <stdexcept>

namespace penumbra {

// Settings the GPU renderer cannot honour: out of range, or beyond the GL implementation.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Settings within the renderer's own ranges that this GL implementation cannot hold (e.g. an
// image larger than its textures); the CLI reports these with the GPU exit code.
class GlLimitError : public RenderError {
 public:
  using RenderError::RenderError;
};

}  // namespace penumbra
