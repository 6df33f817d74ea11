#include "scene/emission.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>
#include <string_view>

#include "scene/video.h"

namespace penumbra {

namespace {

bool isVideoFile(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  constexpr std::array<std::string_view, 5> kVideoExtensions = {".mp4", ".webm", ".mkv", ".avi",
                                                                ".mov"};
  return std::find(kVideoExtensions.begin(), kVideoExtensions.end(), extension) !=
         kVideoExtensions.end();
}

}  // namespace

StillImageSource::StillImageSource(const std::filesystem::path& file)
    : file_(file), image_(loadImage(file)) {}

std::unique_ptr<TextureSource> openTextureSource(const std::filesystem::path& file) {
  if (isVideoFile(file))
    return std::make_unique<VideoSource>(file);
  return std::make_unique<StillImageSource>(file);
}

}  // namespace penumbra
