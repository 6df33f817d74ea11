#include "app/command_failure.h"

#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "app/statistics_json.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/render_error.h"
#include "scene/scene_desc.h"
#include "scene/video.h"

namespace penumbra::app {
namespace {

int report(const std::string& message, int exitCode) {
  std::fflush(stdout);
  std::fprintf(stderr, "penumbra: error: %s\n", message.c_str());
  return exitCode;
}

}  // namespace

CommandFailure glErrorsFailure(std::size_t errorCount) {
  return {kExitFailure, "the GL driver reported " + std::to_string(errorCount) +
                            (errorCount == 1 ? " error" : " errors") + " (printed above)"};
}

void throwIfGlErrors() {
  gl::drainErrors();
  if (gl::errorCount() > 0)
    throw glErrorsFailure(gl::errorCount());
}

int reportFailure() {
  try {
    throw;
  } catch (const CommandFailure& failure) {
    return report(failure.message, failure.exitCode);
  } catch (const SceneError& error) {
    // Located in a scene file: the scene format's own style, FILE:LINE:COL: error: MESSAGE.
    std::fflush(stdout);
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  } catch (const VideoError& error) {
    // A video texture whose damage its index did not show, found while rendering.
    return report(error.what(), kExitBadInput);
  } catch (const ImageError& error) {
    // Images read as input are checked where they are read; what is left is writing one.
    return report(error.what(), kExitOutput);
  } catch (const OutputError& error) {
    return report(error.what(), kExitOutput);
  } catch (const gl::ContextError& error) {
    return report(error.what(), kExitGpu);
  } catch (const gl::ShaderError& error) {
    return report(error.what(), kExitGpu);
  } catch (const GlLimitError& error) {
    return report(error.what(), kExitGpu);
  } catch (const RenderError& error) {
    return report(error.what(), kExitUsage);
  }
}

int reportParseError(const CLI::App& app, const CLI::ParseError& error) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    // --help: CLI11 prints the help of the command it was given for.
    return app.exit(error);
  }
  return report(std::string(error.what()) + " (see --help)", kExitUsage);
}

}  // namespace penumbra::app
