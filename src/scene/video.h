#pragma once
// Video textures: a file decoded with FFmpeg, its 8-bit sRGB frames turned into linear images.
//
// Time: the video loops; the frame for scene time s is the one whose presentation interval
// contains s mod duration, times counted from the first frame. The frame times come from an
// index of every packet built when the file is opened, in the stream's own clock ticks, so the
// choice of frame is exact integer arithmetic.
//
// Threads: a background thread decodes the frames that follow the last one asked for into a small
// queue, so that increasing times (a rendered sequence, or the viewer's wall clock) find their
// frame ready. Any other time (backwards, or far ahead) restarts the thread there: it seeks to
// the keyframe at or before the frame and decodes forward. Both paths decode a frame from the
// same keyframe, so the picture for a time never depends on thread timing or on earlier calls.

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "scene/emission.h"

namespace penumbra {

// A video that cannot be read: an ImageError, told apart so that damage found while rendering is
// reported as bad input and not as an image that could not be written.
class VideoError : public ImageError {
 public:
  using ImageError::ImageError;
};

class VideoSource final : public TextureSource {
 public:
  // Opens and indexes `file` and decodes its first frame. Throws VideoError naming the file and
  // the problem: missing, not a video, no video stream, damaged or truncated data.
  explicit VideoSource(const std::filesystem::path& file);
  ~VideoSource() override;
  VideoSource(const VideoSource&) = delete;
  VideoSource& operator=(const VideoSource&) = delete;

  glm::ivec2 size() const override { return size_; }
  // The frame shown at `seconds` (row 0 at the top, linear RGB, alpha 1). The reference stays
  // valid until the next call; one caller at a time. Throws VideoError when the frame cannot be
  // decoded or `seconds` is not finite.
  const Image& frameAt(double seconds) override;
  bool animated() const override { return true; }
  const std::filesystem::path& file() const override { return file_; }

  int frameCount() const;
  double durationSeconds() const;

 private:
  class Decoder;
  struct DecodedFrame {
    std::int64_t sequence = 0;  // loop * frameCount() + frame index
    Image image;
  };

  std::int64_t sequenceAt(double seconds) const;
  // The background thread's loop.
  void decodeAhead();

  std::filesystem::path file_;
  glm::ivec2 size_{0};
  // Used by the constructor, then by the background thread alone.
  std::unique_ptr<Decoder> decoder_;

  // The caller's side.
  Image current_;
  std::int64_t currentSequence_ = 0;

  // Shared with the background thread, under mutex_.
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<DecodedFrame> queue_;         // consecutive sequences, starting at nextSequence_
  std::int64_t nextSequence_ = 0;          // where the queue continues
  std::optional<std::int64_t> restartAt_;  // a request for the thread to decode from here
  std::optional<std::string> error_;       // the thread's failure, cleared by a restart
  bool stopping_ = false;

  std::thread thread_;
};

}  // namespace penumbra
