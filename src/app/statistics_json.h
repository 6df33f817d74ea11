#pragma once
// Frame statistics as text and JSON (schema in docs/bench.md), and atomic text output.

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "render/frame.h"

namespace penumbra::app {

nlohmann::json statisticsJson(const FrameStatistics& statistics, const RenderSettings& settings);
// Every setting of the GPU renderer (the statistics' settings fields, and the shadows').
nlohmann::json renderSettingsJson(const RenderSettings& settings);
void printStatistics(const FrameStatistics& statistics, std::FILE* out);
// The device profile (device_profile.h) as bench's and --stats-json's "device_profile".
nlohmann::json deviceProfileJson(const DeviceProfile& profile);

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes through a temporary file and a rename; throws OutputError naming the file.
void writeTextFile(const std::filesystem::path& file, const std::string& text);

}  // namespace penumbra::app
