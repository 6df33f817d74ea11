#include "app/size_option.h"

#include <cstdio>

namespace penumbra::app {

std::optional<glm::ivec2> parseImageSize(const std::string& text) {
  int width = 0;
  int height = 0;
  char separator = 0;
  char trailing = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &separator, &height, &trailing) != 3 ||
      separator != 'x' || width < 1 || height < 1) {
    return std::nullopt;
  }
  return glm::ivec2(width, height);
}

CLI::Validator imageSizeValidator() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        if (parseImageSize(text))
          return {};
        return "expected WIDTHxHEIGHT with positive integers (e.g. 512x512), found '" + text + "'";
      },
      "WIDTHxHEIGHT");
}

}  // namespace penumbra::app
