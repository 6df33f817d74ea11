#include "render/device_profile.h"

#include "shared.h"

namespace penumbra {
namespace {

bool isSoftwareRasteriser(const std::string& renderer) {
  return renderer.find("llvmpipe") != std::string::npos ||
         renderer.find("softpipe") != std::string::npos;
}

}  // namespace

DeviceProfile DeviceProfile::portable() {
  DeviceProfile profile;
  profile.renderer = "any device";
  profile.shadowRaysPerDispatch = gpu::kShadowRaysPerDispatch;
  return profile;
}

DeviceProfile deviceProfileFor(const gl::ContextInfo& context) {
  DeviceProfile profile = DeviceProfile::portable();
  profile.renderer = context.renderer;
  profile.software = isSoftwareRasteriser(context.renderer);
  // Timer queries that pass the context's check can still be llvmpipe's (a later Mesa may
  // answer differently): its CPU clock is the time that matters there.
  profile.timing = context.timerQueries && !profile.software ? TimingMethod::GpuTimerQueries
                                                             : TimingMethod::CpuAfterFinish;
  if (!profile.software)
    profile.shadowRaysPerDispatch = gpu::kMaxShadowedVpls;
  return profile;
}

const char* deviceKindName(const DeviceProfile& profile) {
  return profile.software ? "software" : "gpu";
}

const char* secondaryVplSamplingName(SecondaryVplSampling sampling) {
  switch (sampling) {
    case SecondaryVplSampling::Cpu:
      break;
  }
  return "cpu";
}

std::string describe(const DeviceProfile& profile) {
  return profile.renderer + ": " + deviceKindName(profile) + "; timing " +
         timingMethodName(profile.timing) + "; " + std::to_string(profile.shadowRaysPerDispatch) +
         " shadow rays per dispatch; secondary VPLs sampled on the " +
         secondaryVplSamplingName(profile.secondaryVplSampling);
}

}  // namespace penumbra
