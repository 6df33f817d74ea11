#include "fuzz_entries.h"

#include <array>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include <unistd.h>

#include "image/image.h"
#include "scene/model.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace penumbra::fuzz {
namespace {

// The loaders read files by name (the file's extension picks the importer), so each input goes
// through a file: in /dev/shm where it exists, so that a run costs no disk writes. The directory
// is removed when the process exits normally.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    const std::filesystem::path shm("/dev/shm");
    const std::filesystem::path base =
        std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
    path_ = base / ("penumbra-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::filesystem::path writeInput(std::span<const std::uint8_t> bytes, std::string_view extension) {
  static const ScratchDirectory directory;
  const std::filesystem::path file = directory.path() / ("input" + std::string(extension));
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out)
    throw std::runtime_error("fuzz: cannot write " + file.string());
  return file;
}

// Bits 0-1 of the first byte: .obj, .ply, .gltf, .glb; bits 2-3: normals file, smooth, flat,
// file. The seeds start with '0' to '3' (obj to glb, normals file).
constexpr std::array<std::string_view, 4> kModelExtensions{".obj", ".ply", ".gltf", ".glb"};
constexpr std::array<NormalsMode, 4> kNormalsModes{NormalsMode::File, NormalsMode::Smooth,
                                                   NormalsMode::Flat, NormalsMode::File};

// Bits 0-1 of the first byte: .png, .jpg, .exr, .hdr.
constexpr std::array<std::string_view, 4> kImageExtensions{".png", ".jpg", ".exr", ".hdr"};

}  // namespace

bool parseSceneBytes(std::span<const std::uint8_t> input) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  // The parser checks that models and textures exist, relative to the scene's directory: the
  // repository's scenes/ gives the seeds' assets/... paths something to find.
  static const std::filesystem::path sceneFile =
      std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scenes" / "fuzz-input.scene";
  try {
    parseScene(text, sceneFile);
    return true;
  } catch (const SceneError&) {
    return false;
  }
}

bool loadModelBytes(std::span<const std::uint8_t> input) {
  if (input.empty())
    return false;
  const std::uint8_t selector = input[0];
  const std::filesystem::path file = writeInput(input.subspan(1), kModelExtensions[selector & 3u]);
  try {
    // A scene's loading simplifies each model for the reflective shadow maps as well.
    Model model = loadModel(file, kNormalsModes[(selector >> 2) & 3u]);
    simplifyForMaps(model);
    return true;
  } catch (const ModelError&) {
    return false;
  }
}

bool importGltfBytes(std::span<const std::uint8_t> input) {
  if (input.empty())
    return false;
  const std::filesystem::path file = writeInput(input.subspan(1), input[0] & 1u ? ".glb" : ".gltf");
  try {
    loadScene(parseSceneFile(file));
    return true;
  } catch (const SceneError&) {
    return false;
  }
}

bool loadImageBytes(std::span<const std::uint8_t> input) {
  if (input.empty())
    return false;
  const std::filesystem::path file = writeInput(input.subspan(1), kImageExtensions[input[0] & 3u]);
  try {
    loadImage(file);
    return true;
  } catch (const ImageError&) {
    return false;
  }
}

}  // namespace penumbra::fuzz
