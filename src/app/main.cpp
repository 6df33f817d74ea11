// penumbra: render, compare (and later view, bench) from one command line.

#include <cstdio>

#include <CLI/CLI.hpp>

#include "app/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"Penumbra: multiresolution image-space lighting from textured area lights"};
  app.require_subcommand(1);
  penumbra::app::addRenderCommand(app);
  penumbra::app::addCompareCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : penumbra::app::kExitUsage;
  }
  return penumbra::app::kExitOk;
}
