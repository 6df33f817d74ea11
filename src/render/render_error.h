#pragma once

#include <stdexcept>

namespace penumbra {

// Settings the GPU renderer cannot honour: out of range, or beyond the GL implementation.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace penumbra
