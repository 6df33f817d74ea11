// penumbra: render, compare (and later view, bench) from one command line.

#include <cstdio>

#include <CLI/CLI.hpp>

#include "app/command_failure.h"
#include "app/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"Penumbra: multiresolution image-space lighting from textured area lights"};
  app.require_subcommand(1);
  int exitCode = penumbra::app::kExitOk;
  penumbra::app::addRenderCommand(app, exitCode);
  penumbra::app::addCompareCommand(app, exitCode);
  penumbra::app::addBenchCommand(app, exitCode);
  penumbra::app::addViewCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return penumbra::app::reportParseError(app, error);
  }
  return exitCode;
}
