#pragma once
// The one exception type of the Penumbra library.

#include <stdexcept>
#include <string>

namespace penumbra::api {

class Error : public std::runtime_error {
 public:
  enum class Kind {
    BadInput,  // a scene file, its assets or a setting: the message says where and what
    Gpu,       // no GL 4.5 core context, a shader that does not compile, a size beyond GL's limits
    Output,    // an image that cannot be written
  };
  Error(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

}  // namespace penumbra::api
