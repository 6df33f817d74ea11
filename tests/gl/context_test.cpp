#include "gl/context.h"

#include <string>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl/debug.h"
#include "gl_test_environment.h"

namespace penumbra::gl {
namespace {

TEST(ContextTest, IsOpenGl45CoreWithDebugOutput) {
  GLint major = 0;
  GLint minor = 0;
  GLint profile = 0;
  GLint flags = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  EXPECT_TRUE(major > 4 || (major == 4 && minor >= 5)) << major << "." << minor;
  EXPECT_NE(profile & GL_CONTEXT_CORE_PROFILE_BIT, 0);
  EXPECT_NE(flags & GL_CONTEXT_FLAG_DEBUG_BIT, 0);
  EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS));
}

TEST(ContextTest, InfoDescribesTheCurrentContext) {
  const ContextInfo& info = test::testContextInfo();
  EXPECT_EQ(info.vendor, reinterpret_cast<const char*>(glGetString(GL_VENDOR)));
  EXPECT_EQ(info.renderer, reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
  EXPECT_EQ(info.version, reinterpret_cast<const char*>(glGetString(GL_VERSION)));
  EXPECT_TRUE(info.platform == "device" || info.platform == "surfaceless") << info.platform;
  EXPECT_EQ(queryContextInfo("surfaceless").platform, "surfaceless");
}

TEST(ContextTest, DeliberateGlErrorIsCounted) {
  resetErrorCount();
  constexpr GLenum kNotABufferTarget = GL_TEXTURE_2D;
  glBindBuffer(kNotABufferTarget, 0);
  // Synchronous debug output has counted the error before the call returned.
  EXPECT_GE(errorCount(), 1u);
  const std::size_t reportedByCallback = errorCount();
  // glGetError still holds the flag; draining counts it as well and clears it.
  drainErrors();
  EXPECT_EQ(errorCount(), reportedByCallback + 1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // The error was deliberate: keep the listener from failing this test.
  resetErrorCount();
  EXPECT_EQ(errorCount(), 0u);
}

TEST(ContextTest, DrainingWithoutErrorsCountsNothing) {
  resetErrorCount();
  drainErrors();
  EXPECT_EQ(errorCount(), 0u);
}

}  // namespace
}  // namespace penumbra::gl
