#pragma once
// Image and window sizes on the command line: WIDTHxHEIGHT, e.g. 512x512.

#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

namespace penumbra::app {

// The size, or nothing when `text` is not two positive integers joined by 'x'.
std::optional<glm::ivec2> parseImageSize(const std::string& text);

// Rejects values that parseImageSize does not accept, with the expected form in the message.
CLI::Validator imageSizeValidator();

}  // namespace penumbra::app
