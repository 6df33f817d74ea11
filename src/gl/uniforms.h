#pragma once
// Typed uniform setters by name (glProgramUniform*: no need to bind the program first).

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
inline void setUniform(const Program& program, const char* name, bool value) {
  glProgramUniform1i(program.id(), program.uniform(name), value ? 1 : 0);
}
inline void setUniform(const Program& program, const char* name, glm::ivec2 value) {
  glProgramUniform2i(program.id(), program.uniform(name), value.x, value.y);
}
inline void setUniform(const Program& program, const char* name, glm::vec3 value) {
  glProgramUniform3fv(program.id(), program.uniform(name), 1, glm::value_ptr(value));
}
inline void setUniform(const Program& program, const char* name, const glm::mat4& value) {
  glProgramUniformMatrix4fv(program.id(), program.uniform(name), 1, GL_FALSE,
                            glm::value_ptr(value));
}

}  // namespace penumbra::gl
