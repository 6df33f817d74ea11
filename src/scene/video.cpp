#include "scene/video.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "image/ffmpeg_log.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

namespace penumbra {
namespace {

// Frames decoded ahead of the last one asked for: enough to hide a frame's decoding time from
// a caller that advances one frame at a time, small enough for large videos.
constexpr std::size_t kQueueCapacity = 4;
// A time at most this many frames past the queue is reached by decoding forward; further ahead a
// seek is cheaper.
constexpr std::int64_t kLongestForwardDecode = 60;

std::int64_t floorDivide(std::int64_t value, std::int64_t divisor) {
  const std::int64_t quotient = value / divisor;
  return (value % divisor != 0 && value < 0) ? quotient - 1 : quotient;
}

std::int64_t floorModulo(std::int64_t value, std::int64_t divisor) {
  return value - floorDivide(value, divisor) * divisor;
}

bool isFullRange(const AVFrame& frame) {
  const auto format = static_cast<AVPixelFormat>(frame.format);
  return frame.color_range == AVCOL_RANGE_JPEG || format == AV_PIX_FMT_YUVJ420P ||
         format == AV_PIX_FMT_YUVJ422P || format == AV_PIX_FMT_YUVJ444P;
}

}  // namespace

// FFmpeg's demuxer, decoder and converter for one file, with the index of its frame times.
class VideoSource::Decoder {
 public:
  explicit Decoder(const std::filesystem::path& file) : fileName_(file.string()) {
    // A constructor that throws runs no destructor.
    try {
      open();
    } catch (...) {
      release();
      throw;
    }
  }

  ~Decoder() { release(); }

  Decoder(const Decoder&) = delete;
  Decoder& operator=(const Decoder&) = delete;

  glm::ivec2 size() const { return size_; }
  int frameCount() const { return static_cast<int>(frameTicks_.size()); }
  // Immutable after construction, so the caller's thread reads them while the background thread
  // decodes.
  const std::vector<std::int64_t>& frameTicks() const { return frameTicks_; }
  std::int64_t durationTicks() const { return durationTicks_; }
  AVRational timeBase() const { return timeBase_; }

  // Frame `index` (of the sorted frame times) into `image`: decoding on from the last frame when
  // it comes next, seeking otherwise.
  void decode(int index, Image& image) {
    const bool decodingOn = index == nextIndex_;
    // Unknown until this frame decodes: after a failure, the next frame seeks.
    nextIndex_ = -1;
    if (!decodingOn)
      positionBefore(index);
    const std::int64_t target = frameTicks_[static_cast<std::size_t>(index)];
    for (;;) {
      if (!holdingFrame_ && !receiveFrame())
        fail("the data ends before the frame at " + secondsText(target));
      holdingFrame_ = false;
      const std::int64_t ticks = ticksOf(*frame_);
      if (ticks < target)
        continue;
      if (ticks > target)
        fail("the frame at " + secondsText(target) + " cannot be decoded");
      convert(*frame_, image);
      nextIndex_ = index + 1 < frameCount() ? index + 1 : -1;
      return;
    }
  }

 private:
  void open() {
    silenceFfmpegLog();
    check(avformat_open_input(&format_, fileName_.c_str(), nullptr, nullptr), "cannot open");
    check(avformat_find_stream_info(format_, nullptr), "cannot read the stream information");
    const AVCodec* codec = nullptr;
    stream_ = av_find_best_stream(format_, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    if (stream_ == AVERROR_STREAM_NOT_FOUND)
      fail("the file has no video stream");
    if (stream_ == AVERROR_DECODER_NOT_FOUND)
      fail("FFmpeg has no decoder for its video codec");
    check(stream_, "cannot find the video stream");
    for (unsigned i = 0; i < format_->nb_streams; ++i) {
      if (static_cast<int>(i) != stream_)
        format_->streams[i]->discard = AVDISCARD_ALL;
    }
    const AVStream& stream = *format_->streams[stream_];
    timeBase_ = stream.time_base;
    size_ = {stream.codecpar->width, stream.codecpar->height};
    if (size_.x <= 0 || size_.y <= 0)
      fail("the video stream has no picture size");

    codec_ = avcodec_alloc_context3(codec);
    packet_ = av_packet_alloc();
    frame_ = av_frame_alloc();
    if (codec_ == nullptr || packet_ == nullptr || frame_ == nullptr)
      fail("out of memory");
    check(avcodec_parameters_to_context(codec_, stream.codecpar), "cannot set up the decoder");
    check(avcodec_open2(codec_, codec, nullptr), "cannot open the decoder");

    indexFrames();
    rgbStride_ = (3 * size_.x + 63) / 64 * 64;
    rgb_.resize(static_cast<std::size_t>(rgbStride_) * static_cast<std::size_t>(size_.y));
    for (int code = 0; code < 256; ++code)
      linearOfCode_[static_cast<std::size_t>(code)] =
          srgbToLinear(static_cast<float>(code) / 255.0f);
  }

  void release() {
    sws_freeContext(toRgb_);
    toRgb_ = nullptr;
    av_frame_free(&frame_);
    av_packet_free(&packet_);
    avcodec_free_context(&codec_);
    avformat_close_input(&format_);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw VideoError("video " + fileName_ + ": " + what);
  }
  void check(int code, const std::string& what) const {
    if (code < 0)
      fail(what + ": " + ffmpegErrorText(code));
  }

  std::string secondsText(std::int64_t ticks) const {
    return std::to_string(static_cast<double>(ticks) * av_q2d(timeBase_)) + " s";
  }

  // Ticks since the first frame, of a packet or a decoded frame.
  std::int64_t ticksOf(const AVFrame& frame) const {
    return frame.best_effort_timestamp - firstTimestamp_;
  }

  // Reads every packet of the video stream once, for the presentation time of every frame and
  // the duration of the last; damaged or truncated data shows here, before any rendering.
  void indexFrames() {
    std::vector<std::int64_t> timestamps;
    std::int64_t lastTimestamp = AV_NOPTS_VALUE;
    std::int64_t lastDuration = 0;
    for (;;) {
      const int read = av_read_frame(format_, packet_);
      if (read == AVERROR_EOF)
        break;
      check(read, "cannot read frame " + std::to_string(timestamps.size() + 1));
      const bool ours = packet_->stream_index == stream_;
      const bool corrupt = (packet_->flags & AV_PKT_FLAG_CORRUPT) != 0;
      // Edit lists mark packets before the video's start as discarded; decoders drop them.
      const bool shown = (packet_->flags & AV_PKT_FLAG_DISCARD) == 0;
      const std::int64_t timestamp = packet_->pts != AV_NOPTS_VALUE ? packet_->pts : packet_->dts;
      const std::int64_t duration = packet_->duration;
      av_packet_unref(packet_);
      if (!ours || !shown)
        continue;
      if (corrupt)
        fail("frame " + std::to_string(timestamps.size() + 1) + " is damaged or truncated");
      if (timestamp == AV_NOPTS_VALUE)
        fail("frame " + std::to_string(timestamps.size() + 1) + " has no timestamp");
      timestamps.push_back(timestamp);
      if (lastTimestamp == AV_NOPTS_VALUE || timestamp > lastTimestamp) {
        lastTimestamp = timestamp;
        lastDuration = duration;
      }
    }
    if (timestamps.empty())
      fail("the video stream has no frames");

    std::sort(timestamps.begin(), timestamps.end());
    timestamps.erase(std::unique(timestamps.begin(), timestamps.end()), timestamps.end());
    firstTimestamp_ = timestamps.front();
    for (const std::int64_t timestamp : timestamps)
      frameTicks_.push_back(timestamp - firstTimestamp_);
    if (lastDuration <= 0) {
      // No duration in the container: the last frame lasts as long as the one before it, or a
      // thirtieth of a second in a one-frame video.
      lastDuration = frameTicks_.size() > 1
                         ? frameTicks_.back() - frameTicks_[frameTicks_.size() - 2]
                         : std::max<std::int64_t>(1, av_rescale_q(1, {1, 30}, timeBase_));
    }
    durationTicks_ = frameTicks_.back() + lastDuration;
  }

  // Leaves the decoder so that its next frames lead up to frame `index`: seeks to the keyframe
  // at or before it, and further back while the first keyframe decoded lies after it (B-frames
  // make a keyframe's decoding time earlier than its presentation time; frames shown before an
  // open-GOP keyframe need the keyframe before).
  void positionBefore(int index) {
    const std::int64_t target = frameTicks_[static_cast<std::size_t>(index)];
    std::int64_t seekTicks = target;
    std::int64_t stepBack = std::max<std::int64_t>(1, av_rescale_q(1, {1, 1}, timeBase_));
    for (;;) {
      check(av_seek_frame(format_, stream_, firstTimestamp_ + seekTicks, AVSEEK_FLAG_BACKWARD),
            "cannot seek to " + secondsText(seekTicks));
      avcodec_flush_buffers(codec_);
      inputEnded_ = false;
      holdingFrame_ = false;
      // Frames before the first keyframe after a seek may lack their references: skipped.
      bool keyframeFound = false;
      while (!keyframeFound && receiveFrame())
        keyframeFound = frame_->key_frame != 0;
      if (!keyframeFound)
        fail("no keyframe at or after " + secondsText(seekTicks));
      if (ticksOf(*frame_) <= target) {
        holdingFrame_ = true;
        return;
      }
      if (seekTicks <= 0)
        fail("no keyframe at or before " + secondsText(target));
      seekTicks = std::max<std::int64_t>(0, seekTicks - stepBack);
      stepBack *= 2;
    }
  }

  // The next frame in presentation order into frame_; false at the end of the data.
  bool receiveFrame() {
    for (;;) {
      const int received = avcodec_receive_frame(codec_, frame_);
      if (received == 0)
        return true;
      if (received == AVERROR_EOF)
        return false;
      if (received != AVERROR(EAGAIN))
        check(received, "cannot decode");
      const int read = av_read_frame(format_, packet_);
      if (read == AVERROR_EOF) {
        if (inputEnded_)
          return false;
        inputEnded_ = true;
        check(avcodec_send_packet(codec_, nullptr), "cannot decode");
        continue;
      }
      check(read, "cannot read");
      if (packet_->stream_index == stream_) {
        const int sent = avcodec_send_packet(codec_, packet_);
        av_packet_unref(packet_);
        check(sent, "cannot decode");
      } else {
        av_packet_unref(packet_);
      }
    }
  }

  // 8-bit sRGB through swscale, with the stream's matrix and range, then to linear floats.
  void convert(const AVFrame& frame, Image& image) {
    if (frame.width != size_.x || frame.height != size_.y) {
      fail("a frame is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
           ", the video " + std::to_string(size_.x) + "x" + std::to_string(size_.y));
    }
    const bool fullRange = isFullRange(frame);
    if (toRgb_ == nullptr || frame.format != rgbSource_.format ||
        frame.colorspace != rgbSource_.colorspace || fullRange != rgbSource_.fullRange) {
      toRgb_ = sws_getCachedContext(
          toRgb_, size_.x, size_.y, static_cast<AVPixelFormat>(frame.format), size_.x, size_.y,
          AV_PIX_FMT_RGB24, SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr,
          nullptr);
      if (toRgb_ == nullptr)
        fail("cannot convert its pixel format to RGB");
      // An unspecified matrix reads as BT.601, as FFmpeg's own tools do.
      sws_setColorspaceDetails(toRgb_, sws_getCoefficients(frame.colorspace), fullRange ? 1 : 0,
                               sws_getCoefficients(SWS_CS_DEFAULT), 1, 0, 1 << 16, 1 << 16);
      rgbSource_ = {frame.format, frame.colorspace, fullRange};
    }
    std::uint8_t* const destination[1] = {rgb_.data()};
    const int destinationStride[1] = {rgbStride_};
    sws_scale(toRgb_, frame.data, frame.linesize, 0, size_.y, destination, destinationStride);

    image = Image(size_.x, size_.y, glm::vec4(1.0f));
    for (int y = 0; y < size_.y; ++y) {
      const std::uint8_t* row = &rgb_[static_cast<std::size_t>(y) * rgbStride_];
      for (int x = 0; x < size_.x; ++x) {
        glm::vec4& pixel = image.at(x, y);
        for (int channel = 0; channel < 3; ++channel)
          pixel[channel] = linearOfCode_[row[3 * x + channel]];
      }
    }
  }

  std::string fileName_;
  AVFormatContext* format_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVPacket* packet_ = nullptr;
  AVFrame* frame_ = nullptr;
  int stream_ = -1;
  AVRational timeBase_{1, 1};
  glm::ivec2 size_{0};

  std::int64_t firstTimestamp_ = 0;
  std::vector<std::int64_t> frameTicks_;  // sorted presentation times since the first frame
  std::int64_t durationTicks_ = 0;        // one loop: the last frame's end

  int nextIndex_ = -1;         // the frame that decoding on yields without a seek; -1: unknown
  bool holdingFrame_ = false;  // frame_ holds the next frame already
  bool inputEnded_ = false;    // the decoder has been told that no packets follow

  struct RgbSource {
    int format = -1;
    AVColorSpace colorspace = AVCOL_SPC_UNSPECIFIED;
    bool fullRange = false;
  };
  SwsContext* toRgb_ = nullptr;
  RgbSource rgbSource_;
  int rgbStride_ = 0;
  std::vector<std::uint8_t> rgb_;
  std::array<float, 256> linearOfCode_{};
};

VideoSource::VideoSource(const std::filesystem::path& file)
    : file_(file), decoder_(std::make_unique<Decoder>(file)) {
  size_ = decoder_->size();
  decoder_->decode(0, current_);
  currentSequence_ = 0;
  nextSequence_ = 1;
  restartAt_ = 1;
  thread_ = std::thread([this] { decodeAhead(); });
}

VideoSource::~VideoSource() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

int VideoSource::frameCount() const {
  return decoder_->frameCount();
}

double VideoSource::durationSeconds() const {
  return static_cast<double>(decoder_->durationTicks()) * av_q2d(decoder_->timeBase());
}

std::int64_t VideoSource::sequenceAt(double seconds) const {
  // Beyond this the tick count could overflow; no scene runs for 30 years.
  constexpr double kLongestTime = 1e9;
  if (!std::isfinite(seconds) || std::abs(seconds) > kLongestTime) {
    throw VideoError("video " + file_.string() + ": time " + std::to_string(seconds) +
                     " s is out of range");
  }
  // Rounding to the stream's clock tick makes frame f's time f/30 s land on the tick that a
  // 30 fps video's frame f starts at, whatever the floating-point error of f/30.
  const AVRational timeBase = decoder_->timeBase();
  const auto ticks = static_cast<std::int64_t>(std::llround(
      seconds * static_cast<double>(timeBase.den) / static_cast<double>(timeBase.num)));
  const std::int64_t duration = decoder_->durationTicks();
  const std::int64_t loop = floorDivide(ticks, duration);
  const std::int64_t ticksInLoop = ticks - loop * duration;
  // The last frame starting at or before the time; the first frame starts at tick 0.
  const std::vector<std::int64_t>& starts = decoder_->frameTicks();
  const auto index =
      std::upper_bound(starts.begin(), starts.end(), ticksInLoop) - starts.begin() - 1;
  return loop * frameCount() + index;
}

const Image& VideoSource::frameAt(double seconds) {
  const std::int64_t wanted = sequenceAt(seconds);
  // The same frame in another loop decodes to the same picture.
  if (floorModulo(wanted, frameCount()) == floorModulo(currentSequence_, frameCount()))
    return current_;

  std::unique_lock lock(mutex_);
  if (wanted < nextSequence_ || wanted - nextSequence_ > kLongestForwardDecode) {
    queue_.clear();
    error_.reset();
    restartAt_ = wanted;
    nextSequence_ = wanted;
    changed_.notify_all();
  }
  for (;;) {
    changed_.wait(lock, [this] { return !queue_.empty() || error_.has_value(); });
    if (queue_.empty())
      throw VideoError(*error_);
    DecodedFrame decoded = std::move(queue_.front());
    queue_.pop_front();
    nextSequence_ = decoded.sequence + 1;
    changed_.notify_all();
    if (decoded.sequence == wanted) {
      current_ = std::move(decoded.image);
      currentSequence_ = wanted;
      return current_;
    }
  }
}

void VideoSource::decodeAhead() {
  std::int64_t next = 0;
  bool failed = false;
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] {
      return stopping_ || restartAt_.has_value() || (!failed && queue_.size() < kQueueCapacity);
    });
    if (stopping_)
      return;
    if (restartAt_) {
      next = *restartAt_;
      restartAt_.reset();
      failed = false;
    }
    lock.unlock();
    DecodedFrame decoded{next, Image()};
    std::optional<std::string> error;
    try {
      decoder_->decode(static_cast<int>(floorModulo(next, frameCount())), decoded.image);
    } catch (const ImageError& decodeError) {
      error = decodeError.what();
    }
    lock.lock();
    // A restart asked for meanwhile makes this frame useless.
    if (restartAt_)
      continue;
    if (error) {
      error_ = std::move(error);
      failed = true;
    } else {
      queue_.push_back(std::move(decoded));
      ++next;
    }
    changed_.notify_all();
  }
}

}  // namespace penumbra
