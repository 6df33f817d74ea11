#pragma once
// The GPU tests share one headless GL context, created before the first test; any GL error
// during a test fails that test.

#include "gl/context.h"

namespace penumbra::test {

// The shared context's vendor, renderer, version and platform.
const penumbra::gl::ContextInfo& testContextInfo();

}  // namespace penumbra::test
