// libFuzzer target: see fuzz_entries.h for what one input means, docs/robustness.md for running.

#include <cstddef>
#include <cstdint>

#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  penumbra::fuzz::importGltfBytes({data, size});
  return 0;
}
