#pragma once
// Options whose value is one of a few names (--mode, --voxel-grid, ...): --help lists the names
// and the default, and only the names are accepted, in any case (never the enum's numbers).

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace penumbra::app {

template <typename Choice>
using ChoiceNames = std::vector<std::pair<std::string, Choice>>;

// Adds the option `flags` writing into `value` (which must outlive parsing); its current value
// is shown as the default.
template <typename Choice>
CLI::Option* addChoiceOption(CLI::App& command, const std::string& flags, Choice& value,
                             const ChoiceNames<Choice>& names, const std::string& description) {
  std::vector<std::string> accepted;
  std::string typeName;
  std::string defaultName;
  for (const auto& [name, choice] : names) {
    accepted.push_back(name);
    typeName += (typeName.empty() ? "" : "|") + name;
    if (choice == value)
      defaultName = name;
  }
  // IsMember replaces the text by the name it matched, so the callback sees the exact name; its
  // own description ({a,b}) is left out, the type name already lists the names.
  return command
      .add_option_function<std::string>(
          flags,
          [&value, names](const std::string& text) {
            for (const auto& [name, choice] : names)
              if (name == text)
                value = choice;
          },
          description)
      ->transform(CLI::IsMember(accepted, CLI::ignore_case).description(""))
      ->type_name(typeName)
      ->default_str(defaultName);
}

}  // namespace penumbra::app
