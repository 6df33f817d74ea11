#pragma once
// Each subcommand of `penumbra` registers itself on the CLI11 application.

#include <CLI/CLI.hpp>

namespace penumbra::app {

// Exit codes, documented in docs/cli.md.
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,   // a comparison over tolerance, or another failed check
  kExitUsage = 2,     // bad command-line arguments
  kExitBadInput = 3,  // a scene, model, texture or image that cannot be used
  kExitGpu = 4,       // no EGL, no GL 4.5 core, or a GL limit exceeded
  kExitOutput = 5,    // the output cannot be written
  kExitInterrupted = 130,
};

// Each command stores its result in `exitCode` when it runs.
void addRenderCommand(CLI::App& app, int& exitCode);
void addCompareCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);
void addViewCommand(CLI::App& app, int& exitCode);

}  // namespace penumbra::app
