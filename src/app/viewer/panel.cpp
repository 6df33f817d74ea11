#include "app/viewer/panel.h"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <numeric>
#include <string>

#include <imgui.h>

#include "image/image.h"
#include "render/debug_view_registry.h"
#include "render/levels.h"

namespace penumbra::app {
namespace {

constexpr std::size_t kFrameTimeHistoryLength = 240;
constexpr ImGuiSliderFlags kLogarithmic =
    ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp;

// A combo over an enum class whose values are 0, 1, ... in the order of `names`.
template <class Enum>
bool enumCombo(const char* label, Enum& value, std::initializer_list<const char*> names) {
  const std::vector<const char*> items(names);
  int index = static_cast<int>(value);
  if (!ImGui::Combo(label, &index, items.data(), static_cast<int>(items.size())))
    return false;
  value = static_cast<Enum>(index);
  return true;
}

// VPL counts are squares: the slider moves the grid's side and shows the count.
bool vplCountSlider(int& vplsPerLight) {
  int cells = cellsPerSideFor(vplsPerLight);
  const std::string format = std::to_string(vplsPerLight) + " (%d per side)";
  if (!ImGui::SliderInt("VPLs per light", &cells, 1, cellsPerSideFor(gpu::kMaxVplsPerLight),
                        format.c_str(), ImGuiSliderFlags_AlwaysClamp))
    return false;
  vplsPerLight = cells * cells;
  return true;
}

// Screen-grid depth slices come in words of 32.
bool depthSlicesSlider(int& depthSlices) {
  int words = std::max(depthSlices / 32, 1);
  const std::string format = std::to_string(depthSlices) + " slices";
  if (!ImGui::SliderInt("depth slices", &words, 1, 32, format.c_str(),
                        ImGuiSliderFlags_AlwaysClamp))
    return false;
  depthSlices = 32 * words;
  return true;
}

ImU32 displayColour(glm::vec3 linear) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(linearToSrgb(std::clamp(linear.r, 0.0f, 1.0f)),
                                               linearToSrgb(std::clamp(linear.g, 0.0f, 1.0f)),
                                               linearToSrgb(std::clamp(linear.b, 0.0f, 1.0f)),
                                               1.0f));
}

std::string formatValue(float value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", static_cast<double>(value));
  return text;
}

// The colour map as display.frag applies it, with the values at its ends and middle.
void colourMapBar(glm::vec2 range) {
  constexpr int kSegments = 32;
  const float width = ImGui::GetContentRegionAvail().x;
  const float height = ImGui::GetTextLineHeight();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList& drawList = *ImGui::GetWindowDrawList();
  for (int segment = 0; segment < kSegments; ++segment) {
    const float t0 = static_cast<float>(segment) / kSegments;
    const float t1 = static_cast<float>(segment + 1) / kSegments;
    const ImU32 left = displayColour(colourMap(t0));
    const ImU32 right = displayColour(colourMap(t1));
    drawList.AddRectFilledMultiColor(ImVec2(origin.x + t0 * width, origin.y),
                                     ImVec2(origin.x + t1 * width, origin.y + height), left, right,
                                     right, left);
  }
  ImGui::Dummy(ImVec2(width, height));
  const std::string labels[3] = {formatValue(range.x), formatValue(0.5f * (range.x + range.y)),
                                 formatValue(range.y)};
  const float start = ImGui::GetCursorPosX();
  for (int i = 0; i < 3; ++i) {
    // Left, centred and right aligned under the bar.
    const float labelWidth = ImGui::CalcTextSize(labels[i].c_str()).x;
    if (i > 0)
      ImGui::SameLine(start + 0.5f * static_cast<float>(i) * (width - labelWidth));
    ImGui::TextUnformatted(labels[i].c_str());
  }
}

void sectionTitle(const char* title) {
  ImGui::Separator();
  ImGui::TextDisabled("%s", title);
}

}  // namespace

bool drawSettingsPanel(RenderSettings& settings, glm::ivec2 imageSize) {
  bool changed = false;
  changed |= enumCombo("mode", settings.mode, {"hierarchical", "naive"});
  changed |= vplCountSlider(settings.vplsPerLight);

  MultiresolutionSettings& multiresolution = settings.multiresolution;
  sectionTitle("multiresolution");
  ImGui::BeginDisabled(settings.mode != RenderMode::Hierarchical);
  changed |= ImGui::SliderInt("coarsest level", &multiresolution.coarsestSize, 1, 1024, "%d texels",
                              kLogarithmic);
  ImGui::Text("%d levels from %dx%d", levelCountFor(imageSize, multiresolution.coarsestSize),
              imageSize.x, imageSize.y);
  changed |= ImGui::SliderFloat("depth threshold", &multiresolution.depthThreshold, 0.1f, 100.0f,
                                "%.3g", kLogarithmic);
  changed |= ImGui::SliderFloat("normal threshold", &multiresolution.normalThreshold, 0.001f, 2.0f,
                                "%.3g", kLogarithmic);
  changed |= ImGui::SliderFloat("plane tolerance", &multiresolution.planeTolerance, 0.001f, 1.0f,
                                "%.3g", kLogarithmic);
  changed |=
      ImGui::SliderFloat("light proximity threshold", &multiresolution.lightProximityThreshold,
                         0.01f, 10.0f, "%.3g", kLogarithmic);
  ImGui::EndDisabled();

  ShadowSettings& shadows = settings.shadows;
  VoxelSettings& voxels = shadows.voxels;
  sectionTitle("shadows");
  changed |= ImGui::Checkbox("shadows", &shadows.enabled);
  ImGui::BeginDisabled(!shadows.enabled);
  changed |= enumCombo("visibility", shadows.visibility, {"voxels", "bvh"});
  changed |= enumCombo("voxel grid", voxels.grid, {"world", "screen"});
  changed |= enumCombo("voxel fill", voxels.fill, {"surface", "solid"});
  changed |= enumCombo("voxel shape", voxels.shape, {"equal", "cubic"});
  changed |= ImGui::SliderInt(
      "voxel resolution", &voxels.resolution, 8, 1024,
      voxels.shape == VoxelSettings::Shape::Equal ? "%d per axis" : "%d^3 voxels", kLogarithmic);
  ImGui::BeginDisabled(voxels.grid != VoxelSettings::Grid::Screen);
  changed |= depthSlicesSlider(voxels.depthSlices);
  ImGui::EndDisabled();
  changed |= enumCombo("traversal", voxels.traversal, {"uniform", "dda"});
  ImGui::BeginDisabled(voxels.traversal != VoxelSettings::Traversal::Uniform);
  changed |= ImGui::SliderInt("ray steps", &voxels.steps, 1, 512, "%d", kLogarithmic);
  ImGui::EndDisabled();
  changed |= ImGui::Checkbox("widen (2x2x2 voxels per sample)", &voxels.widen);
  ImGui::BeginDisabled(shadows.visibility == ShadowSettings::Visibility::Voxels &&
                       (voxels.grid != VoxelSettings::Grid::World || voxels.widen));
  changed |= ImGui::Checkbox("clear-light test (same masks, fewer rays)", &shadows.clearLightTest);
  ImGui::EndDisabled();
  changed |= ImGui::SliderFloat("shadow offset", &voxels.originOffset, 0.0f, 8.0f,
                                "%.2f voxel diagonals", ImGuiSliderFlags_AlwaysClamp);
  changed |= enumCombo("visibility measure", shadows.refinement.measure,
                       {"xor (differing VPLs)", "count (occluded VPLs)"});
  changed |= ImGui::SliderFloat("visibility threshold", &shadows.refinement.threshold, 0.0f, 1.0f,
                                "%.3f of the VPLs", ImGuiSliderFlags_AlwaysClamp);
  changed |= ImGui::Checkbox("shared VPLs (2x2 pixels trace a quarter each)",
                             &shadows.refinement.shareVplsInBlocks);
  changed |= ImGui::Checkbox("visible fraction (thesis shortcut)", &shadows.visibleFraction);
  changed |= ImGui::Checkbox("reuse visibility while nothing moves", &settings.reuseVisibility);
  ImGui::EndDisabled();

  IndirectSettings& indirect = settings.indirect;
  sectionTitle("indirect light (one bounce)");
  changed |= ImGui::Checkbox("indirect", &indirect.enabled);
  ImGui::BeginDisabled(!indirect.enabled);
  changed |= ImGui::SliderInt("secondary VPLs", &indirect.vplCount, 1, gpu::kMaxSecondaryVpls, "%d",
                              kLogarithmic);
  changed |=
      ImGui::SliderInt("shadow map face", &indirect.rsmSize, 8, 256, "%d texels", kLogarithmic);
  ImGui::BeginDisabled(settings.mode != RenderMode::Hierarchical);
  changed |= ImGui::SliderInt("indirect gather size", &indirect.gatherSize, 1, 1024, "%d texels",
                              kLogarithmic);
  changed |= ImGui::SliderFloat("indirect plane tolerance", &indirect.planeTolerance, 0.001f, 1.0f,
                                "%.3g", kLogarithmic);
  ImGui::EndDisabled();
  ImGui::TextDisabled("view 'indirect' shows the term alone");
  ImGui::EndDisabled();
  return changed;
}

bool drawLegend(DebugViewSource& view, float exposure) {
  if (view.kind == gpu::kDisplayRadiance) {
    ImGui::Text("linear radiance x 2^%.2f, sRGB encoded", static_cast<double>(exposure));
    return false;
  }
  if (view.kind == gpu::kDisplayScalar) {
    ImGui::TextWrapped("%s", view.quantity.c_str());
    colourMapBar(view.range);
    if (!view.fitRange)
      return false;
    ImGui::DragFloatRange2("range", &view.range.x, &view.range.y,
                           0.01f * std::max(view.range.y - view.range.x, 1e-3f));
    return ImGui::Button("fit range to the picture");
  }
  for (std::size_t i = 0; i < view.palette.size(); ++i) {
    const LegendEntry& entry = view.palette[i];
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float side = ImGui::GetTextLineHeight();
    ImGui::GetWindowDrawList()->AddRectFilled(origin, ImVec2(origin.x + side, origin.y + side),
                                              displayColour(entry.colour));
    ImGui::Dummy(ImVec2(side, side));
    ImGui::SameLine();
    ImGui::Text("%zu  %s", i, entry.label.c_str());
  }
  return false;
}

void FrameTimeHistory::add(double milliseconds) {
  values_.push_back(static_cast<float>(milliseconds));
  if (values_.size() > kFrameTimeHistoryLength)
    values_.pop_front();
}

float FrameTimeHistory::mean() const {
  if (values_.empty())
    return 0.0f;
  return std::accumulate(values_.begin(), values_.end(), 0.0f) / static_cast<float>(values_.size());
}

void drawTimings(const std::vector<StageTime>& passes, TimingMethod method,
                 const FrameTimeHistory& frameTimes) {
  const std::vector<float> values(frameTimes.values().begin(), frameTimes.values().end());
  const float mean = frameTimes.mean();
  const std::string overlay = "mean " + std::to_string(static_cast<int>(mean + 0.5f)) + " ms";
  const float highest = values.empty() ? 1.0f : *std::max_element(values.begin(), values.end());
  ImGui::PlotLines("frame (ms)", values.data(), static_cast<int>(values.size()), 0, overlay.c_str(),
                   0.0f, 1.1f * highest, ImVec2(0.0f, 60.0f));
  ImGui::Text("passes (%s)", timingMethodName(method));
  double total = 0.0;
  for (const StageTime& pass : passes)
    total += pass.milliseconds;
  if (!ImGui::BeginTable("passes", 3, ImGuiTableFlags_SizingStretchProp))
    return;
  for (const StageTime& pass : passes) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(stageLabel(pass.key).c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%8.2f ms", pass.milliseconds);
    ImGui::TableNextColumn();
    ImGui::ProgressBar(total > 0.0 ? static_cast<float>(pass.milliseconds / total) : 0.0f,
                       ImVec2(-1.0f, 0.0f), "");
  }
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted("total");
  ImGui::TableNextColumn();
  ImGui::Text("%8.2f ms", total);
  ImGui::EndTable();
}

void drawHelp() {
  static constexpr std::pair<const char*, const char*> kControls[] = {
      {"left drag", "orbit about the target"},
      {"wheel", "zoom toward the target"},
      {"W A S D", "fly forward, left, back, right"},
      {"Q E", "fly down, up"},
      {"R", "reset to the scene's camera"},
      {"space", "pause or resume the animation"},
      {"P", "save a screenshot (penumbra-NNNN.png)"},
      {"F5", "reload shaders (a failed reload keeps the old ones)"},
      {"H", "show or hide this help"},
      {"Esc", "quit"}};
  if (ImGui::BeginTable("controls", 2)) {
    // The keys are short: the actions get the rest of the panel's width.
    ImGui::TableSetupColumn("key", ImGuiTableColumnFlags_WidthFixed, ImGui::GetFontSize() * 6.0f);
    ImGui::TableSetupColumn("action", ImGuiTableColumnFlags_WidthStretch);
    for (const auto& [key, action] : kControls) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(key);
      ImGui::TableNextColumn();
      ImGui::TextWrapped("%s", action);
    }
    ImGui::EndTable();
  }
  ImGui::TextWrapped(
      "The panel changes every setting live; mouse and keys act on the picture when the pointer "
      "is over it.");
}

}  // namespace penumbra::app
