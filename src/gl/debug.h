#pragma once
// KHR_debug output: every message goes to the log (stderr); errors are counted so that tests
// can fail on any GL error.

#include <cstddef>

namespace penumbra::gl {

// Installs the debug callback on the current context (needs a debug context for synchronous
// messages). Notifications are dropped; everything else is printed.
// Test-only: with the environment variable PENUMBRA_TEST_GL_ERROR=1 it then issues one invalid
// GL call (binding a buffer name that was never generated), so that the tests of docs/cli.md's
// exit codes can check that a command run with a GL error exits non-zero. Nothing else reads
// the variable; it is not for users.
void enableDebugOutput();

// Number of GL_DEBUG_TYPE_ERROR messages and glGetError() failures seen since the last reset.
// Shader compiler messages are printed but not counted: Program reports them as ShaderError.
std::size_t errorCount();
void resetErrorCount();

// Calls glGetError() until it returns GL_NO_ERROR, counting what it found.
void drainErrors();

}  // namespace penumbra::gl
