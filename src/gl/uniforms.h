#pragma once
// Typed uniform setters by name (glProgramUniform*: no need to bind the program first). Each
// throws UniformError, naming the program and the uniform, when the program has no active
// uniform of that name (Program::uniform says why a declared one can be missing too).

#include <span>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/program.h"

namespace penumbra::gl {

inline void setUniform(const Program& program, const char* name, float value) {
  glProgramUniform1f(program.id(), program.uniform(name), value);
}
inline void setUniform(const Program& program, const char* name, int value) {
  glProgramUniform1i(program.id(), program.uniform(name), value);
}
inline void setUniform(const Program& program, const char* name, unsigned value) {
  glProgramUniform1ui(program.id(), program.uniform(name), value);
}
inline void setUniform(const Program& program, const char* name, bool value) {
  glProgramUniform1i(program.id(), program.uniform(name), value ? 1 : 0);
}
inline void setUniform(const Program& program, const char* name, glm::vec2 value) {
  glProgramUniform2fv(program.id(), program.uniform(name), 1, glm::value_ptr(value));
}
inline void setUniform(const Program& program, const char* name, glm::ivec2 value) {
  glProgramUniform2i(program.id(), program.uniform(name), value.x, value.y);
}
inline void setUniform(const Program& program, const char* name, glm::uvec2 value) {
  glProgramUniform2ui(program.id(), program.uniform(name), value.x, value.y);
}
inline void setUniform(const Program& program, const char* name, glm::vec3 value) {
  glProgramUniform3fv(program.id(), program.uniform(name), 1, glm::value_ptr(value));
}
inline void setUniform(const Program& program, const char* name, glm::vec4 value) {
  glProgramUniform4fv(program.id(), program.uniform(name), 1, glm::value_ptr(value));
}
inline void setUniform(const Program& program, const char* name, const glm::mat4& value) {
  glProgramUniformMatrix4fv(program.id(), program.uniform(name), 1, GL_FALSE,
                            glm::value_ptr(value));
}
// A `vec3 name[N]` array from its first element on.
inline void setUniform(const Program& program, const char* name,
                       std::span<const glm::vec3> values) {
  glProgramUniform3fv(program.id(), program.uniform(name), static_cast<GLsizei>(values.size()),
                      glm::value_ptr(values.front()));
}

}  // namespace penumbra::gl
