// penumbra: render, compare, bench and view from one command line.

#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "app/command_failure.h"
#include "app/commands.h"
#include "gl/context.h"

namespace {

// `penumbra --version`: the version, and the GL renderer a headless context gets here, which is
// what every GPU command would use (a GPU's EGL device, or llvmpipe).
std::string versionText() {
  std::string text = "penumbra " PENUMBRA_VERSION "\n";
  try {
    const penumbra::gl::HeadlessContext context;
    const penumbra::gl::ContextInfo& info = context.info();
    text += "GL renderer: " + info.renderer + " (" + info.vendor + "; OpenGL " + info.version +
            "; EGL " + info.platform + ")";
  } catch (const penumbra::gl::ContextError& error) {
    text += std::string("GL renderer: none: ") + error.what();
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Penumbra: multiresolution image-space lighting from textured area lights"};
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText, "Print the version and the GL renderer in use");
  int exitCode = penumbra::app::kExitOk;
  penumbra::app::addRenderCommand(app, exitCode);
  penumbra::app::addCompareCommand(app, exitCode);
  penumbra::app::addBenchCommand(app, exitCode);
#ifdef PENUMBRA_HAS_VIEWER
  penumbra::app::addViewCommand(app, exitCode);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return penumbra::app::reportParseError(app, error);
  }
  return exitCode;
}
