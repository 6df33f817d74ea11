#pragma once
// What the renderer does differently per device, chosen once from the GL context (its vendor and
// renderer strings, and whether its timer queries measure anything) and nowhere else:
//
// - timing: GL timer queries on real GPUs; the CPU clock after glFinish on a software
//   rasteriser (Mesa's llvmpipe), whose timer queries answer 1 ns for any work and whose "GPU"
//   is the CPU anyway.
// - shadowRaysPerDispatch: shadow rays one shader invocation traces per dispatch, in the naive
//   gather (its VPL batches) and in the visibility trace (32 per mask word). llvmpipe ends an
//   invocation's loops after 65535 iterations in all, so there passes split their rays over
//   dispatches of kShadowRaysPerDispatch (32); a GPU traces up to kMaxShadowedVpls in one. The
//   sums and masks are the same either way: only the number of dispatches changes.
// - secondaryVplSampling: where the secondary VPLs are sampled from the reflective shadow maps.
//   On the CPU on every device today (secondary_vpls.h says why that costs little).
// - gatherVpls: where the gathers read the VPLs: from a uniform block on every device today,
//   where they fit in one (shaders/gather_vpls.glsl says why); the tests ask for the storage
//   buffer too. The images are the same either way.
//
// `penumbra bench` and `penumbra render --stats` print the profile (docs/bench.md).

#include <string>

#include "gl/context.h"
#include "render/timing.h"
#include "render/vpls.h"

namespace penumbra {

enum class SecondaryVplSampling { Cpu };

struct DeviceProfile {
  std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  bool software = true;  // a software rasteriser (Mesa's llvmpipe or softpipe)
  TimingMethod timing = TimingMethod::CpuAfterFinish;
  int shadowRaysPerDispatch = 32;
  SecondaryVplSampling secondaryVplSampling = SecondaryVplSampling::Cpu;
  GatherVplSource gatherVpls = GatherVplSource::UniformBlock;

  // The profile that works on any device: llvmpipe's. Tests and programs without a context's
  // strings at hand use it.
  static DeviceProfile portable();
};

DeviceProfile deviceProfileFor(const gl::ContextInfo& context);

// "software" or "gpu"; "cpu" for SecondaryVplSampling::Cpu.
const char* deviceKindName(const DeviceProfile& profile);
const char* secondaryVplSamplingName(SecondaryVplSampling sampling);

// One line for logs: "llvmpipe (...): software; timing cpu-after-glfinish; 32 shadow rays per
// dispatch; secondary VPLs sampled on the cpu".
std::string describe(const DeviceProfile& profile);

}  // namespace penumbra
