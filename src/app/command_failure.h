#pragma once
// How every command ends: the one mapping from failures to exit codes (docs/cli.md) and to the
// one line on standard error that reports them.

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

namespace penumbra::app {

// A failure a command finds itself, thrown with the exit code of its kind.
struct CommandFailure {
  int exitCode;
  std::string message;
};

// The failure of a run whose GL context reported `errorCount` errors (the debug output printed
// each as it happened): exit 1, as for any failed check.
CommandFailure glErrorsFailure(std::size_t errorCount);

// Throws glErrorsFailure when GL reported any error since the program started: the debug
// output's count, after draining glGetError on the current context. `render` calls it before
// writing each frame and `bench` before its results, so that no output comes from such a run.
void throwIfGlErrors();

// Called in a command's `catch (...)`: prints the failure being handled (CommandFailure, a
// scene, image, GL or settings error) as one line and returns its exit code. Any other
// exception is rethrown.
int reportFailure();

// Prints the option parser's error in the same style (help goes to standard output instead)
// and returns the exit code.
int reportParseError(const CLI::App& app, const CLI::ParseError& error);

}  // namespace penumbra::app
