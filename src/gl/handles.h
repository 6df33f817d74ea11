#pragma once
// Move-only owners of OpenGL objects (direct state access, GL 4.5). Each deletes its object
// when it goes out of scope, so no pass can leak one. Every owner also counts its live objects
// per kind, so that a long run (tests/soak) can check that the count stays constant.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>

#include <epoxy/gl.h>

namespace penumbra::gl {

enum class ObjectKind {
  Buffer,
  Texture,
  Framebuffer,
  VertexArray,
  Query,
  Sampler,
  Shader,
  Program
};
inline constexpr std::size_t kObjectKindCount = 8;

inline const char* objectKindName(ObjectKind kind) {
  constexpr std::array<const char*, kObjectKindCount> names{
      "buffer", "texture", "framebuffer", "vertex array", "query", "sampler", "shader", "program"};
  return names[static_cast<std::size_t>(kind)];
}

namespace detail {
// One relaxed atomic increment per create and decrement per delete: cheap enough to stay on in
// every build, and correct if contexts ever live on several threads.
inline std::array<std::atomic<std::int64_t>, kObjectKindCount> liveObjects{};

inline void countCreated(ObjectKind kind) {
  liveObjects[static_cast<std::size_t>(kind)].fetch_add(1, std::memory_order_relaxed);
}
inline void countDeleted(ObjectKind kind) {
  liveObjects[static_cast<std::size_t>(kind)].fetch_sub(1, std::memory_order_relaxed);
}
}  // namespace detail

// GL objects created through the owners here (and Program) and not yet deleted, over all
// contexts of the process.
inline std::int64_t liveObjectCount(ObjectKind kind) {
  return detail::liveObjects[static_cast<std::size_t>(kind)].load(std::memory_order_relaxed);
}
inline std::int64_t liveObjectCount() {
  std::int64_t total = 0;
  for (std::size_t kind = 0; kind < kObjectKindCount; ++kind)
    total += liveObjectCount(static_cast<ObjectKind>(kind));
  return total;
}

template <class Traits>
class Object {
 public:
  template <class... Args>
  explicit Object(Args... createArgs) : id_(Traits::create(createArgs...)) {
    if (id_ != 0)
      detail::countCreated(Traits::kind);
  }
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
    if (id_ != 0) {
      Traits::destroy(id_);
      detail::countDeleted(Traits::kind);
    }
    id_ = 0;
  }
  GLuint id_ = 0;
};

struct BufferTraits {
  static constexpr ObjectKind kind = ObjectKind::Buffer;
  static GLuint create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
  static constexpr ObjectKind kind = ObjectKind::Texture;
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static constexpr ObjectKind kind = ObjectKind::Framebuffer;
  static GLuint create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
  static constexpr ObjectKind kind = ObjectKind::VertexArray;
  static GLuint create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct QueryTraits {
  static constexpr ObjectKind kind = ObjectKind::Query;
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};

struct SamplerTraits {
  static constexpr ObjectKind kind = ObjectKind::Sampler;
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
