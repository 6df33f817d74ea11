#pragma once
// What each fuzz target does with one input, shared with the regression test that replays every
// input the fuzzers ever crashed on (tests/fuzz/fuzz_regression_test.cpp).
//
// Each function returns whether the loader accepted the input; a rejection with the loader's
// documented error (SceneError, ModelError, ImageError) returns false. Anything else (another
// exception, a crash, a hang, a sanitizer report) is a finding.

#include <cstddef>
#include <cstdint>
#include <span>

namespace penumbra::fuzz {

// The bytes are scene text, parsed by parseScene as if in the repository's scenes/ directory (no
// model or texture is loaded, but their files must exist).
bool parseSceneBytes(std::span<const std::uint8_t> input);

// The first byte chooses the file type and the normals mode (see kModelExtensions in
// fuzz_entries.cpp); the rest is written to a temporary file and loaded by loadModel. An empty
// input counts as rejected.
bool loadModelBytes(std::span<const std::uint8_t> input);

// Bit 0 of the first byte: .gltf or .glb (the seeds start with '0' or '1'); the rest is written
// to a temporary file and imported as a whole scene (parseSceneFile, then loadScene for the
// textures). An empty input counts as rejected.
bool importGltfBytes(std::span<const std::uint8_t> input);

// The first byte chooses the file type (see kImageExtensions in fuzz_entries.cpp); the rest is
// written to a temporary file and loaded by loadImage. An empty input counts as rejected.
bool loadImageBytes(std::span<const std::uint8_t> input);

}  // namespace penumbra::fuzz
