#pragma once
// GLSL programs from the files of shaders/: by default the copies embedded in the library at
// build time (embedded_shaders.h), or those of a shader directory (the viewer's hot reload, a
// shader developer's PENUMBRA_SHADER_DIR). `#include "name"` is expanded from the same place,
// and the `#extension GL_GOOGLE_include_directive` line that lets glslangValidator check the
// same file at build time is dropped. When compiling on a driver with
// GL_ARB_shading_language_include, that line becomes its #extension instead and #line names the
// included file, so that compile errors read "common.glsl:12(3): error ..." on any driver.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace penumbra::gl {

class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A uniform set by name that the program does not have. A ShaderError, so that the viewer's hot
// reload reports it like a compile error and the commands exit as for one (docs/cli.md).
class UniformError : public ShaderError {
 public:
  using ShaderError::ShaderError;
};

// Where programs read their shader files: PENUMBRA_SHADER_DIR when it is set and not empty, else
// the directory chosen with setShaderDirectory, else nullopt: the embedded copies.
std::optional<std::filesystem::path> shaderDirectory();
// nullopt goes back to the embedded copies. Not thread-safe: choose before compiling programs.
void setShaderDirectory(std::optional<std::filesystem::path> directory);
// The shaders/ folder of the source tree the library was built from, which may be gone.
std::filesystem::path sourceShaderDirectory();
// Where shaderDirectory() reads from, in words for messages.
std::string shaderOrigin();

// Source of a shader file with its includes expanded (each file once); throws ShaderError.
std::string loadShaderSource(const std::string& fileName);

class Program {
 public:
  // A compute program from e.g. "gather_naive.comp"; `defines` are macros #defined before its
  // first line (after #version), e.g. the variants of shadow_rays.glsl.
  static Program compute(const std::string& fileName, const std::vector<std::string>& defines = {});
  // A raster program from a vertex and a fragment shader; `fragmentDefines` as `defines` above,
  // for the fragment shader.
  static Program graphics(const std::string& vertexFile, const std::string& fragmentFile,
                          const std::vector<std::string>& fragmentDefines = {});

  Program() = default;
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;

  GLuint id() const { return id_; }
  // The shader files it was built from, e.g. "display.vert + display.frag", for messages.
  const std::string& name() const { return name_; }
  void use() const { glUseProgram(id_); }
  // Work-group size declared by a compute shader (local_size_x/y/z).
  glm::uvec3 workGroupSize() const { return workGroupSize_; }
  // Number of work groups that cover `threads` threads in each dimension.
  glm::uvec3 groupsFor(glm::uvec3 threads) const;

  // Location of the active uniform `name`. Throws UniformError, naming the program and the
  // uniform, when there is none: a misspelt name, or a uniform the GLSL compiler removed because
  // no code path reads it (GL cannot tell the two apart). So every uniform the C++ side sets must
  // be read by its shader; one that a shader stops reading is an error at its first use, not a
  // silently ignored value (with hot reload, a wrong image and no message).
  GLint uniform(const char* uniformName) const;

 private:
  GLuint id_ = 0;
  std::string name_;
  glm::uvec3 workGroupSize_{0};
};

}  // namespace penumbra::gl
