#include "app/render_options.h"

#include <string>

#include "app/choice_option.h"

namespace penumbra::app {

void addRenderSettingsOptions(CLI::App& command, RenderSettings& settings) {
  command.add_option("--vpls", settings.vplsPerLight, "VPLs per light: a square number, 1 to 1024")
      ->capture_default_str();
  command.add_flag_callback(
      "--no-reuse", [&settings] { settings.reuseVisibility = false; },
      "Trace visibility (and refine and gather) in every frame, even where the last frame's "
      "still holds (the camera, geometry and settings unchanged)");

  MultiresolutionSettings& multiresolution = settings.multiresolution;
  const std::string hierarchy = "Multiresolution gather";
  command
      .add_option("--coarsest", multiresolution.coarsestSize,
                  "Larger side of the coarsest level, in texels")
      ->capture_default_str()
      ->group(hierarchy);
  command
      .add_option("--depth-threshold", multiresolution.depthThreshold,
                  "Refine where |grad z|/z times the image's larger side exceeds this")
      ->capture_default_str()
      ->group(hierarchy);
  command
      .add_option("--normal-threshold", multiresolution.normalThreshold,
                  "Refine where |N1 - N2| between neighbouring pixels exceeds this")
      ->capture_default_str()
      ->group(hierarchy);
  command
      .add_option("--plane-tolerance", multiresolution.planeTolerance,
                  "Upsampling trusts coarser texels this close to a texel's tangent plane, and "
                  "a texel takes visibility from its parent only within it and, at full "
                  "resolution, with no other mesh's surface within it (fraction of the "
                  "distance to the eye)")
      ->capture_default_str()
      ->group(hierarchy);
  command
      .add_option("--light-proximity-threshold", multiresolution.lightProximityThreshold,
                  "Refine where a texel's extent exceeds this fraction of its distance to the "
                  "nearest light")
      ->capture_default_str()
      ->group(hierarchy);

  IndirectSettings& indirect = settings.indirect;
  const std::string bounce = "Indirect light (one bounce, docs/indirect.md)";
  command
      .add_flag("--indirect", indirect.enabled,
                "Add one bounce of indirect light (reflective shadow maps and secondary VPLs)")
      ->group(bounce);
  command
      .add_option("--indirect-vpls", indirect.vplCount,
                  "Secondary VPLs in all, placed in proportion to the reflected flux; the "
                  "hierarchical gather interleaves them, a quarter per texel")
      ->capture_default_str()
      ->group(bounce);
  command
      .add_option("--rsm-size", indirect.rsmSize,
                  "Texels per side of each of the five faces of a light's reflective shadow map")
      ->capture_default_str()
      ->group(bounce);
  command
      .add_option("--indirect-gather-size", indirect.gatherSize,
                  "Hierarchical: gather the indirect light at the finest level whose larger side "
                  "is at most this")
      ->capture_default_str()
      ->group(bounce);
  command
      .add_option("--indirect-plane-tolerance", indirect.planeTolerance,
                  "Indirect upsampling trusts coarse texels this close to a pixel's tangent "
                  "plane (fraction of the distance to the eye)")
      ->capture_default_str()
      ->group(bounce);

  ShadowSettings& shadows = settings.shadows;
  VoxelSettings& voxels = shadows.voxels;
  const std::string visibility = "Shadows (voxel visibility)";
  addChoiceOption<ShadowSettings::Visibility>(
      command, "--visibility", shadows.visibility,
      {{"voxels", ShadowSettings::Visibility::Voxels}, {"bvh", ShadowSettings::Visibility::Bvh}},
      "voxels: shadow rays through the voxel grid (the paper's); bvh: exact, through a "
      "hierarchy of the triangles (the voxel options below then do nothing)")
      ->group(visibility);
  addChoiceOption<VoxelSettings::Grid>(
      command, "--voxel-grid", voxels.grid,
      {{"world", VoxelSettings::Grid::World}, {"screen", VoxelSettings::Grid::Screen}},
      "world: a grid over the scene's bounds (sees occluders outside the view); "
      "screen: the paper's grid over the camera frustum")
      ->group(visibility);
  addChoiceOption<VoxelSettings::Fill>(
      command, "--voxel-fill", voxels.fill,
      {{"surface", VoxelSettings::Fill::Surface}, {"solid", VoxelSettings::Fill::Solid}},
      "surface: mark voxels that surfaces touch; solid: also fill closed meshes (XOR)")
      ->group(visibility);
  command
      .add_option("--voxel-resolution", voxels.resolution,
                  "World grid: voxels per axis (--voxel-shape equal), or the side of a cube of as "
                  "many voxels (cubic); screen grid: columns per side")
      ->capture_default_str()
      ->group(visibility);
  addChoiceOption<VoxelSettings::Shape>(
      command, "--voxel-shape", voxels.shape,
      {{"equal", VoxelSettings::Shape::Equal}, {"cubic", VoxelSettings::Shape::Cubic}},
      "World grid: equal: --voxel-resolution voxels along every axis; cubic: as many voxels as a "
      "cube of that side, shared out in proportion to the scene's box (about cubic voxels)")
      ->group(visibility);
  command
      .add_option("--depth-slices", voxels.depthSlices,
                  "Screen grid: slices along the view depth (rounded up to a multiple of 32)")
      ->capture_default_str()
      ->group(visibility);
  addChoiceOption<VoxelSettings::Traversal>(
      command, "--traversal", voxels.traversal,
      {{"dda", VoxelSettings::Traversal::Dda}, {"uniform", VoxelSettings::Traversal::Uniform}},
      "dda: exact voxel walk (world grid); uniform: a fixed number of samples")
      ->group(visibility);
  command.add_option("--ray-steps", voxels.steps, "Uniform traversal: samples per shadow ray")
      ->capture_default_str()
      ->group(visibility);
  command
      .add_flag("--widen", voxels.widen,
                "Test the 2x2x2 voxels nearest each sample, for thin geometry")
      ->group(visibility);
  command
      .add_flag_callback(
          "--no-voxel-boxes", [&voxels] { voxels.boxes = false; },
          "Let every occupied voxel block whole instead of the box and slabs of the surfaces "
          "inside it (faster, and shadows grow by up to a voxel; docs/shadows.md)")
      ->group(visibility);
  command
      .add_flag_callback(
          "--no-clear-light-test", [&shadows] { shadows.clearLightTest = false; },
          "Trace every VPL of a texel instead of first proving whole lights visible through the "
          "voxels' occupancy pyramid or the BVH (the same masks, for measuring the test)")
      ->group(visibility);
  command
      .add_flag_callback(
          "--no-shared-vpls", [&shadows] { shadows.refinement.shareVplsInBlocks = false; },
          "At full resolution, let every texel trace all the VPLs it needs instead of a quarter "
          "of them, taking the rest from its neighbours where they agree (docs/shadows.md)")
      ->group(visibility);
  command
      .add_option("--shadow-offset", voxels.originOffset,
                  "Shadow rays start this many times the reach of their surface's voxels off it "
                  "(a 16th of a voxel for a face parallel to two axes, docs/shadows.md) and stop "
                  "this many voxel layers short of the light's plane")
      ->capture_default_str()
      ->group(visibility);
  addChoiceOption<VisibilityRefinement::Measure>(
      command, "--visibility-measure", shadows.refinement.measure,
      {{"xor", VisibilityRefinement::Measure::XorPopcount},
       {"count", VisibilityRefinement::Measure::OccludedCountDifference}},
      "xor: VPLs whose visibility differs between neighbours; count: difference of the numbers "
      "of occluded VPLs (the thesis)")
      ->group(visibility);
  command
      .add_option("--visibility-threshold", shadows.refinement.threshold,
                  "Refine where the visibility measure exceeds this fraction of the VPLs")
      ->capture_default_str()
      ->group(visibility);
  command
      .add_flag("--visible-fraction", shadows.visibleFraction,
                "Shade with unshadowed light times the visible fraction (the thesis's "
                "shortcut; wrong for lights whose colour varies)")
      ->group(visibility);
}

}  // namespace penumbra::app
