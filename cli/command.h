#pragma once
// Subcommand registry for the `facial` program. Each commands/<name>.cpp
// registers itself with a static CommandRegistrar, so adding a subcommand
// touches one file.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace cli {

// Called once to declare the subcommand's options on `app`; returns the
// function that runs it (exit code) after parsing succeeded.
using CommandSetup = std::function<std::function<int()>(CLI::App& app)>;

struct CommandInfo {
  std::string name;
  std::string description;
  CommandSetup setup;
};

std::vector<CommandInfo>& commandRegistry();

struct CommandRegistrar {
  CommandRegistrar(std::string name, std::string description, CommandSetup setup) {
    commandRegistry().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

}  // namespace cli
