// `facial`: the runtime's command-line front end (info, render, demo, ...).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>

#include "demo/command.h"

namespace cli {
std::vector<CommandInfo>& commandRegistry() {
  static std::vector<CommandInfo> registry;
  return registry;
}
}  // namespace cli

int main(int argc, char** argv) {
  CLI::App app{"facial: real-time facial expression runtime"};
  app.require_subcommand(1);
  std::map<CLI::App*, std::function<int()>> runners;
  // Listed by name: the commands register from static initialisers, whose
  // order across (unity-built) files the language leaves open.
  std::vector<cli::CommandInfo>& commands = cli::commandRegistry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  for (const cli::CommandInfo& info : commands) {
    CLI::App* sub = app.add_subcommand(info.name, info.description);
    runners[sub] = info.setup(*sub);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  for (auto& [sub, run] : runners) {
    if (sub->parsed()) {
      try {
        return run();
      } catch (const std::exception& e) {
        std::fprintf(stderr, "facial %s: error: %s\n", sub->get_name().c_str(), e.what());
        return 1;
      }
    }
  }
  return 1;
}
