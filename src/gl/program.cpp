#include "gl/program.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "gl/embedded_shaders.h"
#include "gl/handles.h"

namespace penumbra::gl {

namespace {

// How the expanded source tells the driver which file a line comes from.
enum class LineDirectives {
  // "#line 12 3": plain GLSL 4.50. Mesa drops the source-string number (its messages always
  // say 0), so this is only for drivers without GL_ARB_shading_language_include.
  numbered,
  // "#line 12 \"common.glsl\"", allowed by GL_ARB_shading_language_include, which replaces the
  // GL_GOOGLE_include_directive line (keeping line numbers): the driver names the file itself.
  named,
};

// A shader's source with its includes expanded, and the file behind each GLSL source-string
// number that its #line directives use (0 is the file itself), to name files in driver logs.
struct ExpandedSource {
  std::string text;
  std::vector<std::string> files;
};

std::string readFile(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!std::filesystem::is_regular_file(path) || !in)
    throw ShaderError("cannot open " + what + " (" + path.string() + ")");
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

// The contents of shader file `name` from `directory`, or from the embedded copies without one.
std::string readShaderFile(const std::optional<std::filesystem::path>& directory,
                           const std::string& name, const std::string& what) {
  if (directory)
    return readFile(*directory / name, what);
  const std::string key = std::filesystem::path(name).lexically_normal().string();
  const auto files = embeddedShaderFiles();
  const auto found = std::lower_bound(
      files.begin(), files.end(), key,
      [](const EmbeddedShaderFile& file, const std::string& wanted) { return file.name < wanted; });
  if (found == files.end() || found->name != key)
    throw ShaderError("cannot open " + what + " (not among the shaders embedded at build time)");
  return std::string(found->contents);
}

class IncludeExpander {
 public:
  // `defines` are macros #defined right after the main file's #version line.
  IncludeExpander(std::optional<std::filesystem::path> directory, LineDirectives lineDirectives,
                  std::vector<std::string> defines = {})
      : directory_(std::move(directory)),
        lineDirectives_(lineDirectives),
        defines_(std::move(defines)) {}

  ExpandedSource expand(const std::string& fileName) {
    included_.insert(identity(fileName));
    const std::string source =
        readShaderFile(directory_, fileName, "shader file \"" + fileName + "\"");
    append(addFile(fileName), source);
    return std::move(result_);
  }

 private:
  // Gives the file its GLSL source-string number.
  std::size_t addFile(const std::string& name) {
    result_.files.push_back(name);
    return result_.files.size() - 1;
  }

  // Appends `source` (of file `sourceNumber`) line by line. Every line that is dropped or replaced
  // leaves its line break, and every expanded include is followed by a #line, so the driver's
  // line numbers are those of the files. Other #include forms stay as they are: shared.h has
  // `#include <cstdint>` for C++ under #ifdef __cplusplus, which the GLSL preprocessor skips
  // (and reports, with its line, where it is not skipped).
  void append(std::size_t sourceNumber, const std::string& source) {
    static const std::regex includeExtension(
        R"(^\s*#\s*extension\s+GL_GOOGLE_include_directive\b.*)");
    static const std::regex includeDirective(R"re(^\s*#\s*include\s+"([^"]+)"\s*(//.*)?)re");
    static const std::regex versionDirective(R"(^\s*#\s*version\b.*)");

    std::istringstream lines(source);
    std::string line;
    for (int lineNumber = 1; std::getline(lines, line); ++lineNumber) {
      if (!line.empty() && line.back() == '\r')
        line.pop_back();
      const std::string location = result_.files[sourceNumber] + ":" + std::to_string(lineNumber);
      std::smatch match;
      if (std::regex_match(line, includeExtension)) {
        includesEnabled_ = true;
        if (lineDirectives_ == LineDirectives::named)
          result_.text += "#extension GL_ARB_shading_language_include : require";
        result_.text += '\n';
      } else if (std::regex_match(line, match, includeDirective)) {
        // glslangValidator insists on the extension too, so a shader that passes here also
        // passes the build-time check.
        if (!includesEnabled_) {
          throw ShaderError(location +
                            ": #include needs \"#extension GL_GOOGLE_include_directive : "
                            "require\" before it");
        }
        include(match[1].str(), location);
        appendLineDirective(lineNumber + 1, sourceNumber);
      } else {
        result_.text += line;
        result_.text += '\n';
        if (sourceNumber == 0 && !defines_.empty() && std::regex_match(line, versionDirective)) {
          for (const std::string& define : defines_)
            result_.text += "#define " + define + "\n";
          // Numbered even with named directives: the extension that allows names comes later.
          result_.text += "#line " + std::to_string(lineNumber + 1) + " 0\n";
        }
      }
    }
  }

  // What makes two include names the same file: the canonical path in a directory (so that
  // "a.glsl" and "./a.glsl" match), the name among the embedded files.
  std::filesystem::path identity(const std::string& name) const {
    return directory_ ? std::filesystem::weakly_canonical(*directory_ / name)
                      : std::filesystem::path(name).lexically_normal();
  }

  void include(const std::string& name, const std::string& includedFrom) {
    if (!included_.insert(identity(name)).second)
      return;
    const std::string source = readShaderFile(
        directory_, name, "shader file \"" + name + "\" included from " + includedFrom);
    const std::size_t sourceNumber = addFile(name);
    appendLineDirective(1, sourceNumber);
    append(sourceNumber, source);
  }

  // The next line is `lineNumber` of the file with `sourceNumber` (in result_.files).
  void appendLineDirective(int lineNumber, std::size_t sourceNumber) {
    result_.text += "#line " + std::to_string(lineNumber) + " ";
    if (lineDirectives_ == LineDirectives::named)
      result_.text += "\"" + result_.files[sourceNumber] + "\"\n";
    else
      result_.text += std::to_string(sourceNumber) + "\n";
  }

  std::optional<std::filesystem::path> directory_;
  LineDirectives lineDirectives_;
  std::vector<std::string> defines_;
  bool includesEnabled_ = false;
  std::set<std::filesystem::path> included_;
  ExpandedSource result_;
};

// Drivers start a message with where it comes from: "0:12(3): error" (Mesa),
// "\"common.glsl\":12(3): error" (Mesa with named #line), "0(12) : error" (NVIDIA),
// "ERROR: 0:12:" (AMD). Puts the plain file name in its place where that is certain.
std::string nameSourceFiles(const std::string& log, const std::vector<std::string>& files,
                            LineDirectives lineDirectives) {
  static const std::regex location(R"re(^((?:ERROR|WARNING): )?(?:(\d+)|"([^"]*)")(?=[:(]\d))re");
  // With numbered #line, 0 may be any file on a driver that drops source-string numbers, as
  // Mesa does; with named #line, 0 can only be the main file, before its first include.
  const bool zeroIsMainFile = lineDirectives == LineDirectives::named || files.size() == 1;
  std::istringstream lines(log);
  std::string named;
  std::string line;
  bool ambiguous = false;
  while (std::getline(lines, line)) {
    std::smatch match;
    if (std::regex_search(line, match, location)) {
      const auto number = match[2].matched ? std::stoul(match[2].str()) : 0;
      if (match[3].matched)
        line = match[1].str() + match[3].str() + match.suffix().str();
      else if (number < files.size() && (number > 0 || zeroIsMainFile))
        line = match[1].str() + files[number] + match.suffix().str();
      else
        ambiguous = true;
    }
    named += line;
    named += '\n';
  }
  if (ambiguous) {
    named += "(source-string numbers:";
    for (std::size_t number = 0; number < files.size(); ++number)
      named += " " + std::to_string(number) + " " + files[number];
    named += "; the driver may report 0 for all)\n";
  }
  return named;
}

// The info log of a shader or a program, through the matching pair of GL queries.
template <class GetParameter, class GetLog>
std::string infoLog(GLuint object, GetParameter getParameter, GetLog getLog) {
  GLint capacity = 0;
  getParameter(object, GL_INFO_LOG_LENGTH, &capacity);
  std::string log(static_cast<std::size_t>(std::max(capacity, 1)), '\0');
  GLsizei written = 0;
  getLog(object, capacity, &written, log.data());
  log.resize(static_cast<std::size_t>(written));
  return log;
}

bool hasText(const std::string& log) {
  return log.find_first_not_of(" \n") != std::string::npos;
}

struct ShaderTraits {
  static constexpr ObjectKind kind = ObjectKind::Shader;
  static GLuint create(GLenum stage) { return glCreateShader(stage); }
  static void destroy(GLuint id) { glDeleteShader(id); }
};
using Shader = Object<ShaderTraits>;

Shader compileShader(GLenum stage, const std::string& fileName,
                     const std::vector<std::string>& defines = {}) {
  const LineDirectives lineDirectives = epoxy_has_gl_extension("GL_ARB_shading_language_include")
                                            ? LineDirectives::named
                                            : LineDirectives::numbered;
  const ExpandedSource source =
      IncludeExpander(shaderDirectory(), lineDirectives, defines).expand(fileName);
  Shader shader(stage);
  const char* text = source.text.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint compiled = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &compiled);
  const std::string log = nameSourceFiles(infoLog(shader.id(), glGetShaderiv, glGetShaderInfoLog),
                                          source.files, lineDirectives);
  if (compiled != GL_TRUE)
    throw ShaderError("compiling " + fileName + " failed:\n" + log);
  if (hasText(log))
    std::fprintf(stderr, "GLSL warnings in %s:\n%s", fileName.c_str(), log.c_str());
  return shader;
}

struct Stage {
  GLenum type;
  const std::string& fileName;
  const std::vector<std::string>& defines;
};

// Returns the program's name for messages: its files joined by " + ".
std::string compileAndLink(GLuint program, std::initializer_list<Stage> stages) {
  std::vector<Shader> shaders;
  std::string names;
  for (const Stage& stage : stages) {
    shaders.push_back(compileShader(stage.type, stage.fileName, stage.defines));
    names += (names.empty() ? "" : " + ") + stage.fileName;
  }
  for (const auto& shader : shaders)
    glAttachShader(program, shader.id());
  glLinkProgram(program);
  for (const auto& shader : shaders)
    glDetachShader(program, shader.id());
  GLint linked = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  const std::string log = infoLog(program, glGetProgramiv, glGetProgramInfoLog);
  if (linked != GL_TRUE)
    throw ShaderError("linking " + names + " failed:\n" + log);
  if (hasText(log))
    std::fprintf(stderr, "GLSL link warnings for %s:\n%s\n", names.c_str(), log.c_str());
  return names;
}

std::optional<std::filesystem::path>& chosenShaderDirectory() {
  static std::optional<std::filesystem::path> directory;
  return directory;
}

}  // namespace

std::optional<std::filesystem::path> shaderDirectory() {
  const char* overridden = std::getenv("PENUMBRA_SHADER_DIR");
  if (overridden != nullptr && *overridden != '\0')
    return overridden;
  return chosenShaderDirectory();
}

void setShaderDirectory(std::optional<std::filesystem::path> directory) {
  chosenShaderDirectory() = std::move(directory);
}

std::filesystem::path sourceShaderDirectory() {
  return PENUMBRA_SOURCE_SHADER_DIR;
}

std::string shaderOrigin() {
  const auto directory = shaderDirectory();
  return directory ? "shaders read from " + directory->string()
                   : std::string("shaders embedded in the library at build time");
}

std::string loadShaderSource(const std::string& fileName) {
  return IncludeExpander(shaderDirectory(), LineDirectives::numbered).expand(fileName).text;
}

Program Program::compute(const std::string& fileName, const std::vector<std::string>& defines) {
  Program program;
  program.id_ = glCreateProgram();
  if (program.id_ != 0)
    detail::countCreated(ObjectKind::Program);
  program.name_ = compileAndLink(program.id_, {{GL_COMPUTE_SHADER, fileName, defines}});
  GLint size[3] = {0, 0, 0};
  glGetProgramiv(program.id_, GL_COMPUTE_WORK_GROUP_SIZE, size);
  program.workGroupSize_ =
      glm::uvec3(static_cast<unsigned>(size[0]), static_cast<unsigned>(size[1]),
                 static_cast<unsigned>(size[2]));
  return program;
}

Program Program::graphics(const std::string& vertexFile, const std::string& fragmentFile,
                          const std::vector<std::string>& fragmentDefines) {
  Program program;
  program.id_ = glCreateProgram();
  if (program.id_ != 0)
    detail::countCreated(ObjectKind::Program);
  const std::vector<std::string> noDefines;
  program.name_ =
      compileAndLink(program.id_, {{GL_VERTEX_SHADER, vertexFile, noDefines},
                                   {GL_FRAGMENT_SHADER, fragmentFile, fragmentDefines}});
  return program;
}

Program::~Program() {
  if (id_ != 0) {
    glDeleteProgram(id_);
    detail::countDeleted(ObjectKind::Program);
  }
}

Program::Program(Program&& other) noexcept
    : id_(std::exchange(other.id_, 0)),
      name_(std::move(other.name_)),
      workGroupSize_(std::exchange(other.workGroupSize_, {})) {}

Program& Program::operator=(Program&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) {
      glDeleteProgram(id_);
      detail::countDeleted(ObjectKind::Program);
    }
    id_ = std::exchange(other.id_, 0);
    name_ = std::move(other.name_);
    workGroupSize_ = std::exchange(other.workGroupSize_, {});
  }
  return *this;
}

GLint Program::uniform(const char* uniformName) const {
  const GLint location = glGetUniformLocation(id_, uniformName);
  if (location < 0) {
    throw UniformError("program " + name_ + " has no active uniform \"" + uniformName +
                       "\" (misspelt, or unused by the shader and removed by the GLSL compiler)");
  }
  return location;
}

glm::uvec3 Program::groupsFor(glm::uvec3 threads) const {
  if (workGroupSize_.x == 0 || workGroupSize_.y == 0 || workGroupSize_.z == 0)
    throw std::logic_error("groupsFor needs a compute program");
  return (threads + workGroupSize_ - 1u) / workGroupSize_;
}

}  // namespace penumbra::gl
