#pragma once
// What the FFmpeg-based readers and writers share.

#include <string>

namespace penumbra {

// FFmpeg's text for an AVERROR code.
std::string ffmpegErrorText(int code);

// Keeps FFmpeg's own log off stderr except for fatal errors: every failure reaches the user as an
// exception naming the file instead, and x264's statistics would only be noise. Process-wide.
void silenceFfmpegLog();

}  // namespace penumbra
