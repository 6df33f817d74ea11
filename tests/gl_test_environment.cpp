#include "gl_test_environment.h"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include <gtest/gtest.h>

#include "gl/debug.h"

namespace penumbra::test {

namespace {

std::unique_ptr<gl::HeadlessContext> sharedContext;

// Creates the context once for the whole run. A machine without one fails the run rather than
// skipping it, so a broken driver cannot pass as green.
class GlEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
    try {
      sharedContext = std::make_unique<gl::HeadlessContext>();
    } catch (const gl::ContextError& error) {
      // Not FAIL(): gtest would report every test as skipped, and ctest counts skips as passes.
      std::fprintf(stderr, "cannot create the OpenGL context for the GPU tests: %s\n",
                   error.what());
      std::exit(EXIT_FAILURE);
    }
    const auto& info = sharedContext->info();
    std::printf("OpenGL: %s | %s | %s (EGL %s, timer queries %s)\n", info.renderer.c_str(),
                info.version.c_str(), info.vendor.c_str(), info.platform.c_str(),
                info.timerQueries ? "work" : "unusable");
    std::fflush(stdout);
    gl::drainErrors();
    EXPECT_EQ(gl::errorCount(), 0u) << "GL errors while creating the context";
    gl::resetErrorCount();
  }

  void TearDown() override { sharedContext.reset(); }
};

// Fails the test during which any GL error was reported, then starts counting afresh.
class GlErrorListener : public ::testing::EmptyTestEventListener {
 public:
  void OnTestEnd(const ::testing::TestInfo&) override {
    gl::drainErrors();
    const std::size_t errors = gl::errorCount();
    gl::resetErrorCount();
    if (errors > 0)
      ADD_FAILURE() << errors << " GL error(s) during this test (see the log above)";
  }
};

}  // namespace

const gl::ContextInfo& testContextInfo() {
  if (!sharedContext)
    throw std::logic_error("the GPU test context does not exist");
  return sharedContext->info();
}

}  // namespace penumbra::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new penumbra::test::GlEnvironment);
  ::testing::UnitTest::GetInstance()->listeners().Append(new penumbra::test::GlErrorListener);
  return RUN_ALL_TESTS();
}
