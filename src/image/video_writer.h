#pragma once
// Encodes a sequence of linear images to a video file (MP4) with FFmpeg: each frame is tone-mapped
// like an 8-bit image output, srgb(clamp(linear * 2^exposure)), and stored as H.264 (libx264),
// or MPEG-4 part 2 when FFmpeg has no libx264.

#include <filesystem>
#include <memory>

#include <glm/glm.hpp>

#include "image/image.h"

namespace penumbra {

struct VideoOptions {
  float exposure = 0.0f;  // stops, as SaveOptions::exposure
  int framesPerSecond = 30;
  int keyframeInterval = 30;  // frames from one keyframe to the next
  // Near-lossless coding (x264 at constant quality 0, MPEG-4 at the finest quantiser): for test
  // videos whose colours must survive. Such H.264 files need a decoder with the High 4:4:4
  // Predictive profile, which FFmpeg has and some players lack.
  bool nearLossless = false;
};

// True for the file names VideoWriter writes (.mp4).
bool isVideoOutput(const std::filesystem::path& file);

class VideoWriter {
 public:
  // Starts `file`, whose frames are `size` pixels; the file appears under its name only when
  // finish() succeeds. Throws ImageError naming the file: unknown extension, odd or empty size
  // (4:2:0 chroma needs even sides), or an encoder that FFmpeg cannot open.
  VideoWriter(const std::filesystem::path& file, glm::ivec2 size, const VideoOptions& options = {});
  // Without a successful finish(), removes the partial file: no half-written output remains.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Appends the next frame (row 0 at the top), which must have the writer's size.
  void write(const Image& frame);
  // Flushes the encoder, completes the file and gives it its name.
  void finish();

  int framesWritten() const { return framesWritten_; }

 private:
  struct Encoder;
  std::unique_ptr<Encoder> encoder_;
  std::filesystem::path file_;
  std::filesystem::path temporary_;
  glm::ivec2 size_;
  float exposureScale_;
  int framesWritten_ = 0;
  bool finished_ = false;
};

}  // namespace penumbra
