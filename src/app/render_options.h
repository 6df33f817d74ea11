#pragma once
// The command-line options of the GPU renderer's settings, shared by render, bench and view.

#include <CLI/CLI.hpp>

#include "render/frame.h"

namespace penumbra::app {

// Adds --vpls, the multiresolution options and the shadow options, writing into `settings`
// (which must outlive parsing). --no-shadows is left to the command: it also concerns the
// reference modes.
void addRenderSettingsOptions(CLI::App& command, RenderSettings& settings);

}  // namespace penumbra::app
