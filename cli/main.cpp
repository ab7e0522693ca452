// `facial`: the runtime's command-line front end (info, render, demo, ...).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "app/program_error.h"
#include "cli/command.h"

namespace cli {
std::vector<CommandInfo>& commandRegistry() {
  static std::vector<CommandInfo> registry;
  return registry;
}
}  // namespace cli

int main(int argc, char** argv) {
  CLI::App app{"facial: real-time facial expression runtime"};
  app.require_subcommand(1);
  // CLI11 quotes what it refuses: a hostile 100 KB argument is shortened like any name.
  app.failure_message([](const CLI::App* program, const CLI::Error& e) {
    return app::shortenEachLine(CLI::FailureMessage::simple(program, e));
  });
  std::map<CLI::App*, std::function<int()>> runners;
  // Listed by name: the commands register from static initialisers, whose
  // order across (unity-built) files the language leaves open.
  std::vector<cli::CommandInfo>& commands = cli::commandRegistry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  for (const cli::CommandInfo& info : commands) {
    CLI::App* sub = app.add_subcommand(info.name, info.description);
    runners[sub] = info.setup(*sub);
  }
  // CLI11 answers --help before it notices an unknown subcommand, so
  // `facial nosuch --help` would print the usage and exit 0.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string_view wanted = argv[1];
    const bool known = std::any_of(commands.begin(), commands.end(), [&](const auto& c) { return c.name == wanted; });
    if (!known) {
      std::string names;
      for (const cli::CommandInfo& info : commands) names += (names.empty() ? "" : ", ") + info.name;
      std::fprintf(stderr, "facial: unknown command '%.*s' (commands: %s)\n", static_cast<int>(std::min<size_t>(wanted.size(), 64)),
                   wanted.data(), names.c_str());
      return 2;
    }
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
        const std::string program = "facial " + sub->get_name();
        return app::ErrorReporter{program}(e.what());
      }
    }
  }
  return 1;
}
