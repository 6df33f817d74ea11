#pragma once
// Move-only owners of OpenGL objects (direct state access, GL 4.5). Each deletes its object
// when it goes out of scope, so no pass can leak one.

#include <utility>

#include <epoxy/gl.h>

namespace penumbra::gl {

template <class Traits>
class Object {
 public:
  template <class... Args>
  explicit Object(Args... createArgs) : id_(Traits::create(createArgs...)) {}
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }

 private:
  void reset() {
    if (id_ != 0)
      Traits::destroy(id_);
    id_ = 0;
  }
  GLuint id_ = 0;
};

struct BufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct QueryTraits {
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};

struct SamplerTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};

using Buffer = Object<BufferTraits>;
using Texture = Object<TextureTraits>;  // Texture(GL_TEXTURE_2D)
using Framebuffer = Object<FramebufferTraits>;
using VertexArray = Object<VertexArrayTraits>;
using Query = Object<QueryTraits>;  // Query(GL_TIME_ELAPSED)
using Sampler = Object<SamplerTraits>;

}  // namespace penumbra::gl
