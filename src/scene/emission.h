#pragma once
// Where a texture's pixels come from. A still image now; a video later replaces it without the
// renderer knowing: every renderer asks for the frame at a scene time.

#include <filesystem>
#include <memory>
#include <utility>

#include "image/image.h"

namespace penumbra {

class TextureSource {
 public:
  virtual ~TextureSource() = default;
  virtual glm::ivec2 size() const = 0;
  // The picture shown at `seconds` of scene time (a still image ignores the time).
  virtual const Image& frameAt(double seconds) = 0;
  virtual bool animated() const = 0;
  virtual const std::filesystem::path& file() const = 0;
};

class StillImageSource final : public TextureSource {
 public:
  explicit StillImageSource(const std::filesystem::path& file);
  glm::ivec2 size() const override { return {image_.width, image_.height}; }
  const Image& frameAt(double) override { return image_; }
  bool animated() const override { return false; }
  const std::filesystem::path& file() const override { return file_; }

 private:
  std::filesystem::path file_;
  Image image_;
};

// A picture given in memory (a scene built through scene_builder.h); file() is empty.
class MemoryImageSource final : public TextureSource {
 public:
  explicit MemoryImageSource(std::shared_ptr<const Image> image) : image_(std::move(image)) {}
  glm::ivec2 size() const override { return {image_->width, image_->height}; }
  const Image& frameAt(double) override { return *image_; }
  bool animated() const override { return false; }
  const std::filesystem::path& file() const override { return file_; }

 private:
  std::shared_ptr<const Image> image_;
  std::filesystem::path file_;
};

// Chooses the source by the file's extension. Throws ImageError naming the file.
std::unique_ptr<TextureSource> openTextureSource(const std::filesystem::path& file);

}  // namespace penumbra
