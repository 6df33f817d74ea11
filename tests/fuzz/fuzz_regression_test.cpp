// Replays inputs through the fuzz targets' own code (fuzz/fuzz_entries.h), in the normal build:
//   tests/data/fuzz/<target>/: inputs that once crashed or hung a loader (found by the fuzzers, or
//     made by hand for the same fault); each must now be rejected with the loader's error;
//   fuzz/corpus/<target>/: the seeds, valid files that each loader must accept, except those of
//     fuzz/corpus/model_loader/nonfinite/, which it must reject.
// A reverted fix shows as a crash, a hang (the CTest timeout) or an accepted input.

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_entries.h"
#include "test_files.h"

namespace penumbra::fuzz {
namespace {

using Entry = bool (*)(std::span<const std::uint8_t>);

std::vector<std::uint8_t> readBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::filesystem::path> filesIn(const std::filesystem::path& directory) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    if (entry.is_regular_file())
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Runs every file of `directory` through `entry`, expecting `accepted`; returns the file count.
std::size_t replay(const std::filesystem::path& directory, Entry entry, bool accepted) {
  const std::vector<std::filesystem::path> files = filesIn(directory);
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    const std::vector<std::uint8_t> bytes = readBytes(file);
    EXPECT_EQ(entry(bytes), accepted) << (accepted ? "rejected" : "accepted");
  }
  return files.size();
}

const std::filesystem::path kRegressions = test::sourceDirectory() / "tests/data/fuzz";
const std::filesystem::path kSeeds = test::sourceDirectory() / "fuzz/corpus";

TEST(FuzzRegression, ModelInputsThatCrashedOrHungAreRejected) {
  EXPECT_GE(replay(kRegressions / "model_loader", loadModelBytes, false), 5u);
}

TEST(FuzzRegression, ImageInputsThatCrashedAreRejected) {
  EXPECT_GE(replay(kRegressions / "image_loader", loadImageBytes, false), 1u);
}

TEST(FuzzRegression, SceneSeedsParse) {
  EXPECT_GE(replay(kSeeds / "scene_parser", parseSceneBytes, true), 4u);
}

TEST(FuzzRegression, ModelSeedsLoad) {
  EXPECT_GE(replay(kSeeds / "model_loader", loadModelBytes, true), 6u);
}

// Seeds of the model fuzzer with a NaN or infinity in a position, normal or texture coordinate,
// in a folder of their own (libFuzzer reads seed folders recursively): each is rejected.
TEST(FuzzRegression, NonFiniteModelSeedsAreRejected) {
  EXPECT_GE(replay(kSeeds / "model_loader/nonfinite", loadModelBytes, false), 6u);
}

TEST(FuzzRegression, GltfSceneSeedsImport) {
  EXPECT_GE(replay(kSeeds / "gltf_scene", importGltfBytes, true), 3u);
}

TEST(FuzzRegression, ImageSeedsLoad) {
  EXPECT_GE(replay(kSeeds / "image_loader", loadImageBytes, true), 7u);
}

// An empty scene text is a valid (empty) scene; the model and image targets need a type byte.
TEST(FuzzRegression, EmptyInputs) {
  EXPECT_TRUE(parseSceneBytes({}));
  EXPECT_FALSE(loadModelBytes({}));
  EXPECT_FALSE(importGltfBytes({}));
  EXPECT_FALSE(loadImageBytes({}));
}

}  // namespace
}  // namespace penumbra::fuzz
