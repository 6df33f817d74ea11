// Video textures: frame selection by time (sequential, random, looped), determinism across
// decoding paths, and clear errors for bad files. The test videos are written by VideoWriter.

#include "scene/video.h"

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/video_writer.h"
#include "test_files.h"

namespace penumbra {
namespace {

constexpr int kFrames = 12;
constexpr glm::ivec2 kSize{64, 48};
// The 16x16 block at the top left shows the frame index; the rest moves, so that a frame
// decoded from the wrong reference frames would differ everywhere.
constexpr int kBlock = 16;

// The 8-bit red of frame `index`'s block: 16 codes apart, far beyond the coding error.
int redCodeOf(int index) {
  return 16 + 16 * index;
}

float linearOfCode(int code) {
  return srgbToLinear(static_cast<float>(code) / 255.0f);
}

Image countingFrame(int index) {
  Image image(kSize.x, kSize.y);
  for (int y = 0; y < kSize.y; ++y) {
    for (int x = 0; x < kSize.x; ++x) {
      const bool inBlock = x < kBlock && y < kBlock;
      image.at(x, y) =
          inBlock
              ? glm::vec4(linearOfCode(redCodeOf(index)), linearOfCode(128), linearOfCode(64), 1.0f)
              : glm::vec4(linearOfCode((x * 4 + index * 8) % 256), linearOfCode((y * 5) % 256),
                          linearOfCode((x + y + index * 16) % 256), 1.0f);
    }
  }
  return image;
}

// Keyframes every 4 frames, so that random access seeks to a keyframe and decodes forward.
std::filesystem::path writeCountingVideo(const std::filesystem::path& directory) {
  const auto file = directory / "counting.mp4";
  VideoOptions options;
  options.keyframeInterval = 4;
  options.nearLossless = true;
  VideoWriter writer(file, kSize, options);
  for (int index = 0; index < kFrames; ++index)
    writer.write(countingFrame(index));
  writer.finish();
  return file;
}

// The frame index that a decoded picture's block shows.
int shownIndex(const Image& frame) {
  const float red = frame.at(kBlock / 2, kBlock / 2).r;
  const int code = static_cast<int>(std::lround(linearToSrgb(red) * 255.0f));
  const int index = static_cast<int>(std::lround((code - 16) / 16.0));
  // 4 codes: BT.709 YCbCr in 8 bits and back moves a flat colour by at most 2 codes; the codes
  // of neighbouring frames are 16 apart.
  EXPECT_NEAR(code, redCodeOf(index), 4) << "red code " << code << " is no frame's";
  return index;
}

double timeOfFrame(int frame) {
  return frame / 30.0;
}

class VideoSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = test::scratchDirectory();
    video_ = writeCountingVideo(directory_);
  }
  std::filesystem::path directory_;
  std::filesystem::path video_;
};

TEST_F(VideoSourceTest, DescribesTheVideo) {
  VideoSource source(video_);
  EXPECT_EQ(source.size(), kSize);
  EXPECT_EQ(source.frameCount(), kFrames);
  EXPECT_DOUBLE_EQ(source.durationSeconds(), kFrames / 30.0);
  EXPECT_TRUE(source.animated());
  EXPECT_TRUE(openTextureSource(video_)->animated());
}

TEST_F(VideoSourceTest, IncreasingTimesGiveTheFrameShownAtEach) {
  VideoSource source(video_);
  for (int frame = 0; frame < kFrames; ++frame) {
    EXPECT_EQ(shownIndex(source.frameAt(timeOfFrame(frame))), frame) << "at frame " << frame;
    // Halfway through a frame's interval, the same frame is still shown.
    EXPECT_EQ(shownIndex(source.frameAt(timeOfFrame(frame) + 0.5 / 30.0)), frame);
  }
}

TEST_F(VideoSourceTest, AnyOrderOfTimesGivesTheFrameShownAtEach) {
  VideoSource source(video_);
  for (const int frame : {7, 2, 11, 0, 5, 5, 9, 1, 3, 10, 4})
    EXPECT_EQ(shownIndex(source.frameAt(timeOfFrame(frame))), frame) << "at frame " << frame;
}

TEST_F(VideoSourceTest, TimesBeyondTheDurationLoop) {
  VideoSource source(video_);
  // One loop after another, continuing past the end.
  for (int frame = 0; frame < 3 * kFrames; ++frame)
    EXPECT_EQ(shownIndex(source.frameAt(timeOfFrame(frame))), frame % kFrames) << frame;
  // Far ahead: 100 s is 250 loops of 0.4 s exactly, so frame 0; 100 s + 5/30 s shows frame 5.
  EXPECT_EQ(shownIndex(source.frameAt(100.0)), 0);
  EXPECT_EQ(shownIndex(source.frameAt(100.0 + timeOfFrame(5))), 5);
}

TEST_F(VideoSourceTest, PicturesDoNotDependOnTheOrderOfRequests) {
  VideoSource sequential(video_);
  std::vector<Image> inOrder;
  for (int frame = 0; frame < kFrames; ++frame)
    inOrder.push_back(sequential.frameAt(timeOfFrame(frame)));

  VideoSource random(video_);
  for (const int frame : {11, 6, 3, 9, 0, 7, 1, 10, 2, 5, 8, 4, 6}) {
    const Image& picture = random.frameAt(timeOfFrame(frame + kFrames));
    EXPECT_EQ(picture.pixels, inOrder[static_cast<std::size_t>(frame)].pixels) << "frame " << frame;
  }
}

TEST_F(VideoSourceTest, FramesAreTheWrittenPicturesInLinearValues) {
  VideoSource source(video_);
  const Image& decoded = source.frameAt(timeOfFrame(3));
  const Image written = countingFrame(3);
  double largestCodeError = 0.0;
  double codeErrorSum = 0.0;
  for (std::size_t i = 0; i < written.pixels.size(); ++i) {
    for (int channel = 0; channel < 3; ++channel) {
      const double error = std::abs(linearToSrgb(decoded.pixels[i][channel]) -
                                    linearToSrgb(written.pixels[i][channel])) *
                           255.0;
      largestCodeError = std::max(largestCodeError, error);
      codeErrorSum += error;
    }
  }
  const double meanCodeError = codeErrorSum / (3.0 * static_cast<double>(written.pixels.size()));
  // Lossless coding in YCbCr, but RGB to 4:2:0 YCbCr and back loses colour detail at the sharp
  // edges of the pattern: up to 45 codes there, 1.6 codes on average (measured). A wrong sRGB
  // decoding, or a mirrored or shifted picture, is off by tens of codes on average.
  EXPECT_LT(meanCodeError, 4.0);
  EXPECT_LT(largestCodeError, 64.0);
  const glm::vec4 block = decoded.at(kBlock / 2, kBlock / 2);
  // A flat colour: the YCbCr round trip moves it by at most 2 codes; 1 code of margin.
  EXPECT_NEAR(block.g, linearOfCode(128), linearOfCode(131) - linearOfCode(128));
  EXPECT_NEAR(block.b, linearOfCode(64), linearOfCode(67) - linearOfCode(64));
  EXPECT_EQ(block.a, 1.0f);
}

// The repository's clip, as an encoder made it (H.264 with B-frames, a keyframe every 30 frames):
// frames reached by seeking equal those decoded in order.
TEST(RepositoryVideo, FramesReachedBySeekingEqualFramesDecodedInOrder) {
  const auto clip = test::sourceDirectory() / "scenes/assets/tv_screen_128x72_30fps.mp4";
  VideoSource sequential(clip);
  ASSERT_EQ(sequential.frameCount(), 240);
  EXPECT_DOUBLE_EQ(sequential.durationSeconds(), 8.0);
  std::vector<Image> inOrder;
  for (int frame = 0; frame < sequential.frameCount(); ++frame)
    inOrder.push_back(sequential.frameAt(timeOfFrame(frame)));

  VideoSource random(clip);
  // Backwards and forwards, beyond the distance decoded forward without a seek: keyframes (0,
  // 60, 120, 180), the frames after and before them, and the last frames.
  for (const int frame : {239, 61, 120, 0, 200, 119, 60, 180, 1, 238})
    EXPECT_EQ(random.frameAt(timeOfFrame(frame)).pixels,
              inOrder[static_cast<std::size_t>(frame)].pixels)
        << "frame " << frame;
}

TEST(VideoSourceErrors, MissingFileNamesTheFile) {
  const auto missing = test::scratchDirectory() / "missing.mp4";
  try {
    VideoSource source(missing);
    FAIL() << "no error for a missing file";
  } catch (const ImageError& error) {
    EXPECT_NE(std::string(error.what()).find(missing.string()), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("No such file"), std::string::npos) << error.what();
  }
}

TEST(VideoSourceErrors, FileThatIsNoVideoIsRefused) {
  std::string garbage;
  for (int i = 0; i < 4096; ++i)
    garbage.push_back(static_cast<char>((i * 7919) % 251));
  const auto file = test::writeFile(test::scratchDirectory(), "garbage.mp4", garbage);
  try {
    VideoSource source(file);
    FAIL() << "no error for garbage";
  } catch (const ImageError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
  }
}

TEST(VideoSourceErrors, TruncatedVideoIsRefusedWhenOpened) {
  const auto directory = test::scratchDirectory();
  const auto whole = writeCountingVideo(directory);
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto file = test::writeFile(directory, "truncated.mp4", bytes.substr(0, bytes.size() / 2));
  try {
    VideoSource source(file);
    FAIL() << "no error for a truncated video";
  } catch (const ImageError& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
  }
}

TEST(VideoWriter, FailureLeavesNoFile) {
  const auto directory = test::scratchDirectory();
  {
    VideoWriter unfinished(directory / "unfinished.mp4", kSize);
    unfinished.write(countingFrame(0));
  }
  EXPECT_THROW(VideoWriter(directory / "odd.mp4", {65, 48}), ImageError);
  EXPECT_THROW(VideoWriter(directory / "wrong.avi", kSize), ImageError);
  {
    VideoWriter wrongFrame(directory / "size.mp4", kSize);
    EXPECT_THROW(wrongFrame.write(Image(32, 32)), ImageError);
  }
  EXPECT_TRUE(std::filesystem::is_empty(directory));
}

}  // namespace
}  // namespace penumbra
