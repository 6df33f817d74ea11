#include "render/debug_views.h"

#include <algorithm>
#include <cctype>
#include <optional>

#include "render/debug_view_colouring.h"

namespace penumbra {
namespace {

struct ParsedName {
  const DebugViewInfo* info = nullptr;
  std::optional<int> index;
};

// "NAME" or "NAME-N" for an indexed view; info null when neither names a view.
ParsedName parseName(const std::string& name) {
  if (const DebugViewInfo* info = findDebugView(name))
    return {info, std::nullopt};
  const std::size_t dash = name.rfind('-');
  if (dash == std::string::npos)
    return {};
  const std::string digits = name.substr(dash + 1);
  const DebugViewInfo* info = findDebugView(name.substr(0, dash));
  if (info == nullptr || !info->indexed || digits.empty() || digits.size() > 5 ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(c) != 0; }))
    return {};
  return {info, std::stoi(digits)};
}

}  // namespace

std::vector<std::string> debugViewNames(const Renderer& renderer) {
  std::vector<std::string> names;
  for (const DebugViewInfo& info : debugViewInfos()) {
    if (!debugViewAvailable(info, renderer, nullptr))
      continue;
    if (!info.indexed) {
      names.emplace_back(info.name);
      continue;
    }
    const glm::ivec2 indices = debugViewIndices(info, renderer);
    for (int index = indices.x; index <= indices.y; ++index)
      names.push_back(std::string(info.name) + "-" + std::to_string(index));
  }
  return names;
}

Image debugView(const Renderer& renderer, const std::string& name, const RenderSettings& settings) {
  const ParsedName parsed = parseName(name);
  if (parsed.info == nullptr) {
    throw RenderError("unknown debug view '" + name + "'; expected one of: " + debugViewNameList());
  }
  const DebugViewInfo& info = *parsed.info;
  std::string why;
  if (!debugViewAvailable(info, renderer, &why))
    throw RenderError(why);
  const glm::ivec2 indices = debugViewIndices(info, renderer);
  const int index = parsed.index.value_or(indices.x);
  if (index < indices.x || index > indices.y) {
    throw RenderError(
        "debug view '" + name +
        "': " + (info.needs == DebugViewNeeds::Shadows ? "the voxel grid's slices" : "its levels") +
        " are " + std::to_string(indices.x) + " to " + std::to_string(indices.y));
  }
  DebugViewSource source = debugViewSource(info, index, renderer, settings);
  if (source.fitRange)
    source.range = valueRange(source);
  return DebugViewColouring().colour(source);
}

}  // namespace penumbra
