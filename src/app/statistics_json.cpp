#include "app/statistics_json.h"

#include <fstream>
#include <optional>

namespace penumbra::app {

namespace {

// The shadow rays the naive mode traces for the same frame: one per lit-surface pixel and VPL.
std::uint64_t naiveShadowRays(const FrameStatistics& statistics) {
  return static_cast<std::uint64_t>(statistics.fullResolutionSamples) *
         static_cast<std::uint64_t>(statistics.vplCount);
}

// Shadow rays per lit-surface pixel: what the naive mode traces per pixel is the VPL count.
double raysPerLitPixel(std::uint64_t rays, const FrameStatistics& statistics) {
  return statistics.fullResolutionSamples > 0
             ? static_cast<double>(rays) / statistics.fullResolutionSamples
             : 0.0;
}

// The share of the texels holding a mask that traced no ray for it (inherited whole from their
// parent, or kept from the last frame); none when no texel holds one.
std::optional<double> shareWithoutRays(unsigned masked, unsigned traced) {
  if (masked == 0)
    return std::nullopt;
  return static_cast<double>(masked - traced) / masked;
}

nlohmann::json optionalJson(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json statisticsJson(const FrameStatistics& statistics, const RenderSettings& settings) {
  nlohmann::json levels = nlohmann::json::array();
  const unsigned gathered = statistics.samplesGathered();
  for (std::size_t level = 0; level < statistics.levels.size(); ++level) {
    const LevelStatistics& stats = statistics.levels[level];
    levels.push_back({
        {"level", level},
        {"width", stats.size.x},
        {"height", stats.size.y},
        {"samples", stats.samples},
        {"share_of_gathered", gathered > 0 ? static_cast<double>(stats.samples) / gathered : 0.0},
        {"share_of_full_resolution",
         statistics.fullResolutionSamples > 0
             ? static_cast<double>(stats.samples) / statistics.fullResolutionSamples
             : 0.0},
        {"visibility_masked_texels", stats.visibilityMasked},
        {"visibility_traced_texels", stats.visibilityTraced},
        {"visibility_clear_texels", stats.visibilityClear},
        {"share_without_rays",
         optionalJson(shareWithoutRays(stats.visibilityMasked, stats.visibilityTraced))},
        {"shadow_rays", stats.shadowRays},
        {"shadow_rays_per_lit_pixel", raysPerLitPixel(stats.shadowRays, statistics)},
    });
  }
  nlohmann::json json = renderSettingsJson(settings);
  json.update({
      {"scene_upload_bytes", statistics.sceneUploadBytes},
      {"full_resolution_samples", statistics.fullResolutionSamples},
      {"samples_gathered", gathered},
      {"ideal_speedup",
       gathered > 0 ? static_cast<double>(statistics.fullResolutionSamples) / gathered : 0.0},
      {"visibility_reused", statistics.visibilityReused},
      {"visibility_structure_kept", statistics.visibilityStructureKept},
      {"gather_vpls_kept", statistics.vplsKept},
      {"bounce_sources_kept", statistics.bounceSourcesKept},
      {"visibility_masked_texels", statistics.visibilityMasked()},
      {"visibility_traced_texels", statistics.visibilityTraced()},
      {"visibility_clear_texels", statistics.visibilityClear()},
      {"share_without_rays", optionalJson(shareWithoutRays(statistics.visibilityMasked(),
                                                           statistics.visibilityTraced()))},
      {"shadow_rays", statistics.shadowRays()},
      {"shadow_rays_per_lit_pixel", raysPerLitPixel(statistics.shadowRays(), statistics)},
      {"naive_shadow_rays", naiveShadowRays(statistics)},
      {"visibility_bytes", statistics.visibilityBytes},
      {"levels", levels},
  });
  return json;
}

nlohmann::json renderSettingsJson(const RenderSettings& settings) {
  const MultiresolutionSettings& multiresolution = settings.multiresolution;
  const VoxelSettings& voxels = settings.shadows.voxels;
  return {
      {"mode", renderModeName(settings.mode)},
      {"vpls_per_light", settings.vplsPerLight},
      {"coarsest_size", multiresolution.coarsestSize},
      {"depth_threshold", multiresolution.depthThreshold},
      {"normal_threshold", multiresolution.normalThreshold},
      {"plane_tolerance", multiresolution.planeTolerance},
      {"light_proximity_threshold", multiresolution.lightProximityThreshold},
      {"reuse_visibility", settings.reuseVisibility},
      {"indirect",
       {{"enabled", settings.indirect.enabled},
        {"vpls", settings.indirect.vplCount},
        {"rsm_size", settings.indirect.rsmSize},
        {"gather_size", settings.indirect.gatherSize},
        {"plane_tolerance", settings.indirect.planeTolerance}}},
      {"shadows",
       {{"enabled", settings.shadows.enabled},
        {"visibility",
         settings.shadows.visibility == ShadowSettings::Visibility::Bvh ? "bvh" : "voxels"},
        {"voxel_grid", voxels.grid == VoxelSettings::Grid::World ? "world" : "screen"},
        {"voxel_fill", voxels.fill == VoxelSettings::Fill::Surface ? "surface" : "solid"},
        {"voxel_shape", voxels.shape == VoxelSettings::Shape::Equal ? "equal" : "cubic"},
        {"voxel_resolution", voxels.resolution},
        {"depth_slices", voxels.depthSlices},
        {"traversal", voxels.traversal == VoxelSettings::Traversal::Dda ? "dda" : "uniform"},
        {"ray_steps", voxels.steps},
        {"widen", voxels.widen},
        {"voxel_boxes", voxels.boxes},
        {"clear_light_test", settings.shadows.clearLightTest},
        {"shadow_offset", voxels.originOffset},
        {"visibility_measure",
         settings.shadows.refinement.measure == VisibilityRefinement::Measure::XorPopcount
             ? "xor"
             : "count"},
        {"visibility_threshold", settings.shadows.refinement.threshold},
        {"shared_vpls", settings.shadows.refinement.shareVplsInBlocks},
        {"visible_fraction", settings.shadows.visibleFraction}}},
  };
}

nlohmann::json deviceProfileJson(const DeviceProfile& profile) {
  return {{"renderer", profile.renderer},
          {"kind", deviceKindName(profile)},
          {"timing_method", timingMethodName(profile.timing)},
          {"shadow_rays_per_dispatch", profile.shadowRaysPerDispatch},
          {"secondary_vpl_sampling", secondaryVplSamplingName(profile.secondaryVplSampling)}};
}

void printStatistics(const FrameStatistics& statistics, std::FILE* out) {
  const unsigned gathered = statistics.samplesGathered();
  std::fprintf(out, "scene data uploaded: %llu bytes\n",
               static_cast<unsigned long long>(statistics.sceneUploadBytes));
  std::fprintf(out, "full-resolution samples (lit-surface pixels): %u\n",
               statistics.fullResolutionSamples);
  if (statistics.vplCount > 0) {
    std::fprintf(
        out, "visibility structure (voxel grid or BVH): %.2f MiB, %s\n",
        static_cast<double>(statistics.visibilityBytes) / (1024.0 * 1024.0),
        statistics.visibilityStructureKept ? "kept from the last frame" : "built in this frame");
    if (!statistics.levels.empty()) {
      std::fprintf(out, "visibility: %s\n",
                   statistics.visibilityReused ? "reused from the last frame (nothing traced)"
                                               : "traced in this frame");
    }
  } else if (statistics.visibilityReused) {
    std::fprintf(out, "hierarchy: reused from the last frame (no discontinuity or refinement)\n");
  }
  if (statistics.vplsKept > 0)
    std::fprintf(out, "gather: the sums of %d VPLs kept from the last frame\n",
                 statistics.vplsKept);
  if (statistics.bounceSourcesKept)
    std::fprintf(out, "indirect light: the maps and secondary VPLs kept from the last frame\n");
  for (std::size_t level = 0; level < statistics.levels.size(); ++level) {
    const LevelStatistics& stats = statistics.levels[level];
    std::fprintf(out, "level %zu (%dx%d): %u samples, %.1f%% of gathered", level, stats.size.x,
                 stats.size.y, stats.samples,
                 gathered > 0 ? 100.0 * stats.samples / gathered : 0.0);
    if (statistics.vplCount > 0) {
      std::fprintf(out, "; visibility masks at %u texels, traced at %u, every light clear at %u",
                   stats.visibilityMasked, stats.visibilityTraced, stats.visibilityClear);
      if (const auto share = shareWithoutRays(stats.visibilityMasked, stats.visibilityTraced))
        std::fprintf(out, " (%.1f%% without per-VPL rays)", 100.0 * *share);
      std::fprintf(out, ", %llu shadow rays (%.2f per lit pixel)",
                   static_cast<unsigned long long>(stats.shadowRays),
                   raysPerLitPixel(stats.shadowRays, statistics));
    }
    std::fputc('\n', out);
  }
  if (!statistics.levels.empty()) {
    std::fprintf(
        out, "gathered %u samples: %.2f%% of a full-resolution gather (ideal speedup %.1fx)\n",
        gathered,
        statistics.fullResolutionSamples > 0 ? 100.0 * gathered / statistics.fullResolutionSamples
                                             : 0.0,
        gathered > 0 ? static_cast<double>(statistics.fullResolutionSamples) / gathered : 0.0);
    const std::uint64_t naiveRays = naiveShadowRays(statistics);
    if (naiveRays > 0) {
      std::fprintf(
          out,
          "shadow rays %llu: %.2f per lit pixel, %.2f%% of the naive mode's %llu (pixels x "
          "VPLs)\n",
          static_cast<unsigned long long>(statistics.shadowRays()),
          raysPerLitPixel(statistics.shadowRays(), statistics),
          100.0 * static_cast<double>(statistics.shadowRays()) / static_cast<double>(naiveRays),
          static_cast<unsigned long long>(naiveRays));
    }
  }
}

void writeTextFile(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::path temporary = file;
  temporary += ".partial";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw OutputError("cannot write " + file.string());
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw OutputError("cannot write " + file.string());
  }
}

}  // namespace penumbra::app
