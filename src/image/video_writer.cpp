#include "image/video_writer.h"

#include <cctype>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include "image/ffmpeg_log.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace penumbra {
namespace {

std::string lowercaseExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace

bool isVideoOutput(const std::filesystem::path& file) {
  return lowercaseExtension(file) == ".mp4";
}

// FFmpeg's objects for one file, freed in reverse order of creation.
struct VideoWriter::Encoder {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;  // owned by `format`
  SwsContext* toYuv = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  std::string fileName;

  ~Encoder() {
    av_packet_free(&packet);
    av_frame_free(&frame);
    sws_freeContext(toYuv);
    avcodec_free_context(&codec);
    if (format != nullptr) {
      avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw ImageError("cannot write video " + fileName + ": " + what);
  }
  void check(int code, const char* what) const {
    if (code < 0)
      fail(std::string(what) + ": " + ffmpegErrorText(code));
  }

  // Moves every packet the encoder has ready into the file.
  void writePackets() {
    for (;;) {
      const int received = avcodec_receive_packet(codec, packet);
      if (received == AVERROR(EAGAIN) || received == AVERROR_EOF)
        return;
      check(received, "encoding failed");
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      check(av_interleaved_write_frame(format, packet), "writing failed");
    }
  }
};

VideoWriter::VideoWriter(const std::filesystem::path& file, glm::ivec2 size,
                         const VideoOptions& options)
    : file_(file),
      temporary_(temporaryPathFor(file)),
      size_(size),
      exposureScale_(std::exp2(options.exposure)) {
  silenceFfmpegLog();
  encoder_ = std::make_unique<Encoder>();
  Encoder& e = *encoder_;
  e.fileName = file.string();
  if (!isVideoOutput(file))
    e.fail("unknown video format '" + file.extension().string() + "' (use .mp4)");
  if (size.x < 2 || size.y < 2 || size.x % 2 != 0 || size.y % 2 != 0) {
    e.fail("the frame size " + std::to_string(size.x) + "x" + std::to_string(size.y) +
           " must have even sides of at least 2 pixels (4:2:0 chroma)");
  }
  if (options.framesPerSecond < 1 || options.keyframeInterval < 1)
    e.fail("frames per second and keyframe interval must be positive");

  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  const bool x264 = codec != nullptr;
  if (!x264)
    codec = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  if (codec == nullptr)
    e.fail("FFmpeg has neither the libx264 nor the mpeg4 encoder");

  // The temporary name has no usable extension, so the container is named explicitly; the
  // name is still needed, since +faststart reopens the file to move the index to the front.
  e.check(avformat_alloc_output_context2(&e.format, nullptr, "mp4", temporary_.c_str()),
          "cannot set up the MP4 container");
  e.codec = avcodec_alloc_context3(codec);
  e.frame = av_frame_alloc();
  e.packet = av_packet_alloc();
  if (e.codec == nullptr || e.frame == nullptr || e.packet == nullptr)
    e.fail("out of memory");

  AVCodecContext& c = *e.codec;
  c.width = size.x;
  c.height = size.y;
  c.time_base = AVRational{1, options.framesPerSecond};
  c.framerate = AVRational{options.framesPerSecond, 1};
  c.pix_fmt = AV_PIX_FMT_YUV420P;
  c.gop_size = options.keyframeInterval;
  // sRGB pictures in BT.709 limited-range YCbCr, labelled so that decoders convert them back
  // with the same matrix (VideoSource does).
  c.color_range = AVCOL_RANGE_MPEG;
  c.colorspace = AVCOL_SPC_BT709;
  c.color_primaries = AVCOL_PRI_BT709;
  c.color_trc = AVCOL_TRC_IEC61966_2_1;
  if ((e.format->oformat->flags & AVFMT_GLOBALHEADER) != 0)
    c.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (x264) {
    // crf 18 is visually lossless for rendered frames; 0 is mathematically lossless in YCbCr.
    av_opt_set(c.priv_data, "crf", options.nearLossless ? "0" : "18", 0);
    av_opt_set(c.priv_data, "preset", "medium", 0);
  } else {
    c.flags |= AV_CODEC_FLAG_QSCALE;
    c.global_quality = FF_QP2LAMBDA * (options.nearLossless ? 1 : 3);
  }
  e.check(avcodec_open2(e.codec, codec, nullptr), "cannot open the encoder");

  e.stream = avformat_new_stream(e.format, nullptr);
  if (e.stream == nullptr)
    e.fail("out of memory");
  e.stream->time_base = c.time_base;
  e.check(avcodec_parameters_from_context(e.stream->codecpar, e.codec),
          "cannot describe the stream");

  e.frame->format = c.pix_fmt;
  e.frame->width = size.x;
  e.frame->height = size.y;
  e.frame->color_range = c.color_range;
  e.frame->colorspace = c.colorspace;
  e.check(av_frame_get_buffer(e.frame, 0), "out of memory");
  e.toYuv = sws_getContext(size.x, size.y, AV_PIX_FMT_RGB24, size.x, size.y, AV_PIX_FMT_YUV420P,
                           SWS_BICUBIC | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
  if (e.toYuv == nullptr)
    e.fail("cannot set up the colour conversion");
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  sws_setColorspaceDetails(e.toYuv, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);

  try {
    e.check(avio_open(&e.format->pb, temporary_.c_str(), AVIO_FLAG_WRITE),
            ("cannot create " + temporary_.string()).c_str());
    // The index goes first, so that players can start before the whole file has arrived.
    AVDictionary* muxerOptions = nullptr;
    av_dict_set(&muxerOptions, "movflags", "+faststart", 0);
    const int written = avformat_write_header(e.format, &muxerOptions);
    av_dict_free(&muxerOptions);
    e.check(written, "cannot write the header");
  } catch (...) {
    encoder_.reset();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw;
  }
}

VideoWriter::~VideoWriter() {
  if (finished_)
    return;
  encoder_.reset();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void VideoWriter::write(const Image& picture) {
  Encoder& e = *encoder_;
  if (finished_)
    e.fail("frame written after finish()");
  if (picture.width != size_.x || picture.height != size_.y) {
    e.fail("frame " + std::to_string(framesWritten_) + " is " + std::to_string(picture.width) +
           "x" + std::to_string(picture.height) + ", expected " + std::to_string(size_.x) + "x" +
           std::to_string(size_.y));
  }
  std::vector<std::uint8_t> rgb(picture.pixels.size() * 3);
  for (std::size_t i = 0; i < picture.pixels.size(); ++i)
    for (int channel = 0; channel < 3; ++channel)
      rgb[i * 3 + channel] = encode8BitSrgb(picture.pixels[i][channel], exposureScale_);

  // The encoder may still hold the previous frame's buffers.
  e.check(av_frame_make_writable(e.frame), "out of memory");
  const std::uint8_t* sourcePlanes[1] = {rgb.data()};
  const int sourceStrides[1] = {3 * size_.x};
  sws_scale(e.toYuv, sourcePlanes, sourceStrides, 0, size_.y, e.frame->data, e.frame->linesize);
  e.frame->pts = framesWritten_;
  e.check(avcodec_send_frame(e.codec, e.frame), "encoding failed");
  e.writePackets();
  ++framesWritten_;
}

void VideoWriter::finish() {
  Encoder& e = *encoder_;
  if (finished_)
    return;
  if (framesWritten_ == 0)
    e.fail("no frames to write");
  e.check(avcodec_send_frame(e.codec, nullptr), "encoding failed");
  e.writePackets();
  e.check(av_write_trailer(e.format), "cannot complete the file");
  e.check(avio_closep(&e.format->pb), "cannot close the file");
  std::error_code renameError;
  std::filesystem::rename(temporary_, file_, renameError);
  if (renameError)
    e.fail(renameError.message());
  finished_ = true;
}

}  // namespace penumbra
