#include "gl/program.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gl/dispatch.h"
#include "gl/embedded_shaders.h"
#include "gl/handles.h"
#include "gl/uniforms.h"
#include "test_files.h"

namespace penumbra::gl {
namespace {

// Points PENUMBRA_SHADER_DIR at `directory` for one test and restores it afterwards.
class ShaderDirectoryOverride {
 public:
  explicit ShaderDirectoryOverride(const std::filesystem::path& directory) {
    if (const char* previous = std::getenv(kVariable))
      previous_ = previous;
    setenv(kVariable, directory.c_str(), 1);
  }
  ~ShaderDirectoryOverride() {
    if (previous_)
      setenv(kVariable, previous_->c_str(), 1);
    else
      unsetenv(kVariable);
  }
  ShaderDirectoryOverride(const ShaderDirectoryOverride&) = delete;
  ShaderDirectoryOverride& operator=(const ShaderDirectoryOverride&) = delete;

 private:
  static constexpr const char* kVariable = "PENUMBRA_SHADER_DIR";
  std::optional<std::string> previous_;
};

template <class Action>
std::string shaderErrorMessage(Action action) {
  try {
    action();
  } catch (const ShaderError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected a ShaderError";
  return "";
}

constexpr const char* kIncludingShader = R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "twice.glsl"
#include "factor.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Output { uint value; };
void main() { value = twice(value); }
)";
constexpr const char* kTwice = R"(#include "factor.glsl"
uint twice(uint x) { return x * kFactor; }
)";
constexpr const char* kFactor = "const uint kFactor = 2u;\n";

TEST(ShaderSourceTest, ExpandsEachIncludeOnceWithLineDirectives) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "main.comp", kIncludingShader);
  test::writeFile(directory, "twice.glsl", kTwice);
  test::writeFile(directory, "factor.glsl", kFactor);
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);

  // The dropped #extension line stays as an empty line; "#line 5 0" resumes main.comp after
  // the second include of factor.glsl was skipped.
  EXPECT_EQ(loadShaderSource("main.comp"), R"(#version 450

#line 1 1
#line 1 2
const uint kFactor = 2u;
#line 2 1
uint twice(uint x) { return x * kFactor; }
#line 4 0
#line 5 0
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Output { uint value; };
void main() { value = twice(value); }
)");
  EXPECT_NE(Program::compute("main.comp").id(), 0u);
}

TEST(ShaderSourceTest, ShaderDirectoryFollowsTheEnvironment) {
  const auto directory = test::scratchDirectory();
  {
    const ShaderDirectoryOverride shaderDirectoryOverride(directory);
    EXPECT_EQ(shaderDirectory(), directory);
    EXPECT_EQ(shaderOrigin(), "shaders read from " + directory.string());
  }
  // An empty value counts as unset: the copies embedded at build time.
  const ShaderDirectoryOverride emptyOverride("");
  EXPECT_EQ(shaderDirectory(), std::nullopt);
  EXPECT_EQ(shaderOrigin(), "shaders embedded in the library at build time");
  // A chosen directory (the viewer's) is used until it is unchosen; the environment wins.
  setShaderDirectory(sourceShaderDirectory());
  EXPECT_EQ(shaderDirectory(), sourceShaderDirectory());
  {
    const ShaderDirectoryOverride shaderDirectoryOverride(directory);
    EXPECT_EQ(shaderDirectory(), directory);
  }
  setShaderDirectory(std::nullopt);
  EXPECT_EQ(shaderDirectory(), std::nullopt);
}

// The embedded copies are the files of shaders/, all of them, byte for byte.
TEST(EmbeddedShadersTest, HoldEveryFileOfTheShaderFolder) {
  std::vector<std::string> names;
  for (const EmbeddedShaderFile& file : embeddedShaderFiles()) {
    names.emplace_back(file.name);
    EXPECT_EQ(file.contents, test::readFile(sourceShaderDirectory() / file.name)) << file.name;
  }
  std::vector<std::string> folder;
  for (const auto& entry : std::filesystem::directory_iterator(sourceShaderDirectory()))
    folder.push_back(entry.path().filename().string());
  std::sort(folder.begin(), folder.end());
  EXPECT_EQ(names, folder);
}

// Without a shader directory every program of the renderer compiles from the embedded copies,
// with the same expanded source as from the folder.
TEST(EmbeddedShadersTest, ExpandLikeTheFolder) {
  const ShaderDirectoryOverride unset("");
  ASSERT_EQ(shaderDirectory(), std::nullopt);
  const std::string embedded = loadShaderSource("gather_hierarchical.comp");
  EXPECT_NE(Program::compute("gather_hierarchical.comp").id(), 0u);
  EXPECT_NE(Program::graphics("gbuffer.vert", "gbuffer_surface.frag").id(), 0u);
  const ShaderDirectoryOverride folder(sourceShaderDirectory());
  EXPECT_EQ(embedded, loadShaderSource("gather_hierarchical.comp"));
}

TEST(EmbeddedShadersTest, MissingFileIsNamed) {
  const ShaderDirectoryOverride unset("");
  const std::string message = shaderErrorMessage([] { loadShaderSource("absent.comp"); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "\"absent.comp\"", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "embedded", message);
}

TEST(ShaderSourceTest, MissingFileIsNamed) {
  const ShaderDirectoryOverride shaderDirectoryOverride(test::scratchDirectory());
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "\"absent.comp\"",
                      shaderErrorMessage([] { loadShaderSource("absent.comp"); }));
}

TEST(ShaderSourceTest, MissingIncludeNamesTheIncludingLine) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "main.comp",
                  "#version 450\n#extension GL_GOOGLE_include_directive : require\n"
                  "#include \"nowhere.glsl\"\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const std::string message = shaderErrorMessage([] { loadShaderSource("main.comp"); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "\"nowhere.glsl\"", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "main.comp:3", message);
}

TEST(ShaderSourceTest, IncludeNeedsTheExtensionLikeGlslangValidator) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "main.comp", "#version 450\n#include \"common.glsl\"\n");
  test::writeFile(directory, "common.glsl", "const uint kOne = 1u;\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const std::string message = shaderErrorMessage([] { loadShaderSource("main.comp"); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "main.comp:2", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "GL_GOOGLE_include_directive", message);
}

TEST(ShaderSourceTest, OtherIncludeFormsAreLeftToTheCompiler) {
  // Like shaders/shared.h, which is also C++: its <cstdint> include is for C++ only.
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "shared.comp",
                  "#version 450\n#ifdef __cplusplus\n#include <cstdint>\n#endif\n"
                  "layout(local_size_x = 1) in;\nvoid main() {}\n");
  test::writeFile(directory, "active.comp",
                  "#version 450\nlayout(local_size_x = 1) in;\n#include <common.glsl>\n"
                  "void main() {}\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "#include <cstdint>",
                      loadShaderSource("shared.comp"));
  EXPECT_NE(Program::compute("shared.comp").id(), 0u);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "active.comp:3",
                      shaderErrorMessage([] { Program::compute("active.comp"); }));
}

TEST(ProgramTest, CompileErrorNamesTheIncludedFileAndLine) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "main.comp",
                  "#version 450\n#extension GL_GOOGLE_include_directive : require\n"
                  "#include \"broken.glsl\"\nlayout(local_size_x = 1) in;\n"
                  "void main() { helper(); }\n");
  test::writeFile(directory, "broken.glsl",
                  "// A helper with a typo.\nvoid helper() {\n"
                  "  undeclaredVariable = 1;\n}\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const std::string message = shaderErrorMessage([] { Program::compute("main.comp"); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "main.comp", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "broken.glsl:3", message);
}

TEST(ProgramTest, CompileErrorAfterAnIncludeNamesTheMainFileAndLine) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "main.comp",
                  "#version 450\n#extension GL_GOOGLE_include_directive : require\n"
                  "#include \"fine.glsl\"\nlayout(local_size_x = 1) in;\n"
                  "void main() {\n  missingFunction();\n}\n");
  test::writeFile(directory, "fine.glsl", "const uint kOne = 1u;\nconst uint kTwo = 2u;\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "main.comp:6",
                      shaderErrorMessage([] { Program::compute("main.comp"); }));
}

// A define chooses the branch of an #ifdef (shadow_rays.glsl's variants), and the main file's
// line numbers stay its own after the lines it adds.
TEST(ProgramTest, DefinesChooseABranchAndKeepTheMainFilesLines) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "variant.comp",
                  "#version 450\nlayout(local_size_x = 1) in;\n"
                  "#ifdef BROKEN_VARIANT\nvoid main() {\n  missingFunction();\n}\n"
                  "#else\nvoid main() {}\n#endif\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  EXPECT_NE(Program::compute("variant.comp").id(), 0u);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "variant.comp:5", shaderErrorMessage([] {
                        Program::compute("variant.comp", {"BROKEN_VARIANT"});
                      }));
}

TEST(ProgramTest, LinkErrorNamesBothFiles) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "plain.vert",
                  "#version 450\nvoid main() { gl_Position = vec4(0); }\n");
  test::writeFile(directory, "needs_input.frag",
                  "#version 450\nin vec3 neverWritten;\nout vec4 color;\n"
                  "void main() { color = vec4(neverWritten, 1); }\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const std::string message =
      shaderErrorMessage([] { Program::graphics("plain.vert", "needs_input.frag"); });
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "plain.vert", message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "needs_input.frag", message);
}

TEST(ProgramTest, GraphicsProgramHasNoWorkGroups) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "plain.vert",
                  "#version 450\nvoid main() { gl_Position = vec4(0); }\n");
  test::writeFile(directory, "white.frag",
                  "#version 450\nout vec4 color;\nvoid main() { color = vec4(1); }\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const Program program = Program::graphics("plain.vert", "white.frag");
  EXPECT_NE(program.id(), 0u);
  EXPECT_EQ(program.workGroupSize(), glm::uvec3(0));
  EXPECT_THROW(program.groupsFor(glm::uvec3(1)), std::logic_error);
}

TEST(ProgramTest, WorkGroupSizeComesFromTheShader) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "tile.comp",
                  "#version 450\nlayout(local_size_x = 8, local_size_y = 4) in;\nvoid main() {}\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const Program program = Program::compute("tile.comp");
  EXPECT_EQ(program.workGroupSize(), glm::uvec3(8, 4, 1));
  EXPECT_EQ(program.groupsFor({16, 8, 1}), glm::uvec3(2, 2, 1));
  EXPECT_EQ(program.groupsFor({17, 9, 1}), glm::uvec3(3, 3, 1));
  EXPECT_EQ(program.groupsFor({1, 1, 1}), glm::uvec3(1, 1, 1));
}

TEST(ProgramTest, MoveTransfersOwnership) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "empty.comp",
                  "#version 450\nlayout(local_size_x = 32) in;\nvoid main() {}\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  Program first = Program::compute("empty.comp");
  const GLuint id = first.id();
  Program second = std::move(first);
  EXPECT_EQ(first.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is defined
  EXPECT_EQ(second.id(), id);
  EXPECT_EQ(second.workGroupSize(), glm::uvec3(32, 1, 1));

  Program third;
  third = std::move(second);
  EXPECT_EQ(third.id(), id);
  EXPECT_TRUE(glIsProgram(id));
  third = Program();
  EXPECT_FALSE(glIsProgram(id));
}

TEST(ProgramTest, ComputeKernelWritesDoubledIndices) {
  const ShaderDirectoryOverride shaderDirectoryOverride(test::sourceDirectory() /
                                                        "tests/data/shaders");
  const Program program = Program::compute("double_index.comp");
  EXPECT_EQ(program.workGroupSize(), glm::uvec3(64, 1, 1));

  constexpr GLuint kValueCount = 1000;  // not a multiple of 64: the last group is partial
  const glm::uvec3 groups = program.groupsFor({kValueCount, 1, 1});
  EXPECT_EQ(groups, glm::uvec3(16, 1, 1));

  Buffer output;
  glNamedBufferStorage(output.id(), kValueCount * sizeof(GLuint), nullptr, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, output.id());
  program.use();
  setUniform(program, "valueCount", kValueCount);
  glDispatchCompute(groups.x, groups.y, groups.z);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);

  std::vector<GLuint> values(kValueCount);
  glGetNamedBufferSubData(output.id(), 0, kValueCount * sizeof(GLuint), values.data());
  for (GLuint index = 0; index < kValueCount; ++index)
    ASSERT_EQ(values[index], index * 2) << "at index " << index;
}

// Linear work past the 65535 work groups along x that GL guarantees (a 512^3 voxel grid's
// transposition needs 65536): dispatchLinear goes on in rows along y, and linear_dispatch.glsl
// gives each item its own index, so that every item is reached once.
TEST(DispatchTest, LinearWorkPastTheWorkGroupLimitReachesEveryItemOnce) {
  const auto directory = test::scratchDirectory();
  test::writeFile(directory, "linear_dispatch.glsl",
                  test::readFile(test::sourceDirectory() / "shaders/linear_dispatch.glsl"));
  test::writeFile(directory, "count_items.comp",
                  "#version 450\n"
                  "#extension GL_GOOGLE_include_directive : require\n"
                  "layout(local_size_x = 64) in;\n"
                  "#include \"linear_dispatch.glsl\"\n"
                  "layout(std430, binding = 0) buffer Counts { uint counts[]; };\n"
                  "uniform uint itemCount;\n"
                  "void main() {\n"
                  "  uint item = linearInvocationIndex();\n"
                  "  if (item < itemCount) atomicAdd(counts[item], 1u);\n"
                  "}\n");
  const ShaderDirectoryOverride shaderDirectoryOverride(directory);
  const Program program = Program::compute("count_items.comp");
  // Two rows of work groups, the last group partial.
  constexpr GLuint kItemCount = kMaxWorkGroupsPerDimension * 64 + 1000;
  Buffer counts;
  const std::vector<GLuint> zeros(kItemCount, 0u);
  glNamedBufferStorage(counts.id(), kItemCount * sizeof(GLuint), zeros.data(), 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counts.id());
  setUniform(program, "itemCount", kItemCount);
  dispatchLinear(program, kItemCount);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  std::vector<GLuint> values(kItemCount);
  glGetNamedBufferSubData(counts.id(), 0, kItemCount * sizeof(GLuint), values.data());
  for (GLuint item = 0; item < kItemCount; ++item)
    ASSERT_EQ(values[item], 1u) << "item " << item;
}

TEST(ProgramTest, SettersOfEachTypeReachTheShader) {
  const ShaderDirectoryOverride shaderDirectoryOverride(test::sourceDirectory() /
                                                        "tests/data/shaders");
  const Program program = Program::compute("uniform_types.comp");
  setUniform(program, "anInt", -7);
  setUniform(program, "anUnsigned", 4000000000u);
  setUniform(program, "aFloat", 0.25f);
  setUniform(program, "aVec2", glm::vec2(1.5f, -2.5f));
  setUniform(program, "anIvec2", glm::ivec2(-3, 9));
  setUniform(program, "aUvec2", glm::uvec2(11u, 12u));
  setUniform(program, "aVec3", glm::vec3(0.5f, 0.75f, -1.0f));
  setUniform(program, "aVec4", glm::vec4(2.0f, 3.0f, 4.0f, 5.0f));

  constexpr int kValueCount = 16;
  Buffer output;
  glNamedBufferStorage(output.id(), kValueCount * sizeof(float), nullptr, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, output.id());
  program.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  std::vector<float> values(kValueCount);
  glGetNamedBufferSubData(output.id(), 0, kValueCount * sizeof(float), values.data());
  // Every value is exact in a float (4e9 is a multiple of 256, within float's 24-bit mantissa).
  const std::vector<float> expected = {-7.0f, 4.0e9f, 0.25f, 1.5f,  -2.5f, -3.0f, 9.0f, 11.0f,
                                       12.0f, 0.5f,   0.75f, -1.0f, 2.0f,  3.0f,  4.0f, 5.0f};
  EXPECT_EQ(values, expected);
}

TEST(ProgramTest, MisspeltUniformThrowsNamingTheProgramAndTheUniform) {
  const ShaderDirectoryOverride shaderDirectoryOverride(test::sourceDirectory() /
                                                        "tests/data/shaders");
  const Program program = Program::compute("double_index.comp");
  const std::string message = shaderErrorMessage([&] { setUniform(program, "valueCuont", 1u); });
  EXPECT_NE(message.find("double_index.comp"), std::string::npos) << message;
  EXPECT_NE(message.find("\"valueCuont\""), std::string::npos) << message;
  EXPECT_THROW(setUniform(program, "valueCuont", 1u), UniformError);
}

// The documented rule (program.h): a declared uniform that the shader does not read is removed
// by the compiler, and setting it is an error like a misspelt name.
TEST(ProgramTest, UniformTheShaderDoesNotReadThrows) {
  const ShaderDirectoryOverride shaderDirectoryOverride(test::sourceDirectory() /
                                                        "tests/data/shaders");
  const Program program = Program::compute("uniform_types.comp");
  const std::string message = shaderErrorMessage([&] { setUniform(program, "notRead", 1.0f); });
  EXPECT_NE(message.find("uniform_types.comp"), std::string::npos) << message;
  EXPECT_NE(message.find("\"notRead\""), std::string::npos) << message;
}

TEST(ProgramTest, GraphicsProgramIsNamedByBothFiles) {
  const Program program = Program::graphics("display.vert", "display.frag");
  EXPECT_EQ(program.name(), "display.vert + display.frag");
  const std::string message = shaderErrorMessage([&] { setUniform(program, "exposure", 1.0f); });
  EXPECT_NE(message.find("display.vert + display.frag"), std::string::npos) << message;
}

}  // namespace
}  // namespace penumbra::gl
