// The one mapping from failures to exit codes (docs/cli.md's table), which every command ends
// with: each kind of failure a command can throw gives its documented code.

#include "app/command_failure.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "app/commands.h"
#include "app/statistics_json.h"
#include "gl/context.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/render_error.h"
#include "scene/scene_desc.h"
#include "scene/video.h"

namespace penumbra::app {
namespace {

// The exit code reportFailure gives `failure`, thrown and caught as a command catches it.
template <class Failure>
int exitCodeOf(const Failure& failure) {
  try {
    throw failure;
  } catch (...) {
    return reportFailure();
  }
}

TEST(ExitCodes, MatchTheDocumentedTable) {
  EXPECT_EQ(exitCodeOf(CommandFailure{kExitFailure, "over tolerance"}), 1);
  EXPECT_EQ(exitCodeOf(glErrorsFailure(2)), 1);
  EXPECT_EQ(exitCodeOf(RenderError("VPL count 3 is not a square number")), 2);
  EXPECT_EQ(exitCodeOf(CommandFailure{kExitUsage, "--aov and --debug-view: choose one"}), 2);
  EXPECT_EQ(exitCodeOf(SceneError({"a.scene", 1, 2}, "unknown keyword")), 3);
  EXPECT_EQ(exitCodeOf(VideoError("a.mp4: frame 3 cannot be decoded")), 3);
  EXPECT_EQ(exitCodeOf(gl::ContextError("no EGL")), 4);
  EXPECT_EQ(exitCodeOf(gl::ShaderError("compiling a.comp failed")), 4);
  EXPECT_EQ(exitCodeOf(gl::UniformError("program a.comp has no active uniform \"b\"")), 4);
  EXPECT_EQ(exitCodeOf(GlLimitError("image size 100000x32 is outside")), 4);
  EXPECT_EQ(exitCodeOf(ImageError("cannot save image out.png")), 5);
  EXPECT_EQ(exitCodeOf(OutputError("cannot write out.json")), 5);
  EXPECT_EQ(exitCodeOf(CommandFailure{kExitInterrupted, "interrupted"}), 130);
}

TEST(ExitCodes, OtherExceptionsAreRethrown) {
  EXPECT_THROW(exitCodeOf(std::logic_error("a bug")), std::logic_error);
}

TEST(ExitCodes, GlErrorsFailureCountsTheErrors) {
  EXPECT_EQ(glErrorsFailure(1).message, "the GL driver reported 1 error (printed above)");
  EXPECT_EQ(glErrorsFailure(3).message, "the GL driver reported 3 errors (printed above)");
}

}  // namespace
}  // namespace penumbra::app
