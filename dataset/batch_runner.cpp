#include "dataset/batch_runner.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/scene/file_bytes.h"

extern char** environ;

namespace dataset {
namespace {

bool schedulerVariable(const char* entry) {
  for (const char* prefix : {"SLURM_ARRAY_", "JOB_COMPLETION_INDEX=", "FACIAL_SHARD_COUNT="})
    if (std::strncmp(entry, prefix, std::strlen(prefix)) == 0) return true;
  return false;
}

std::vector<char*> childEnvironment() {
  std::vector<char*> env;
  for (char** e = environ; *e; ++e)
    if (!schedulerVariable(*e)) env.push_back(*e);
  env.push_back(nullptr);
  return env;
}

// Copies the child's stderr to ours until it closes; returns its last non-blank line.
std::string teeLastLine(int fd) {
  std::string pending, last;
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    (void)!write(STDERR_FILENO, buffer, size_t(n));
    pending.append(buffer, size_t(n));
    for (size_t nl; (nl = pending.find('\n')) != std::string::npos; pending.erase(0, nl + 1))
      if (pending.find_first_not_of(" \t\r\n") < nl) last = pending.substr(0, nl);
  }
  if (pending.find_first_not_of(" \t\r\n") != std::string::npos) last = pending;
  return last;
}

std::string exitProblem(int status) {
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "exit status " + std::to_string(WEXITSTATUS(status));
}

// Runs the process; ok, or the error text.
std::string spawnAndWait(const BatchJob& job, const std::filesystem::path& program, bool& ok) {
  ok = false;
  std::vector<std::string> argv{program.string(), job.kind};
  argv.insert(argv.end(), job.args.begin(), job.args.end());
  std::vector<char*> args;
  for (std::string& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  int pipeFds[2];
  if (pipe(pipeFds) != 0) return std::string("cannot make a pipe: ") + std::strerror(errno);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // The child's stdout ("wrote ...") goes to our stderr, keeping our stdout
  // the result lines alone; its stderr comes through the pipe.
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipeFds[0]);
  std::vector<char*> env = childEnvironment();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  close(pipeFds[1]);
  if (spawned != 0) {
    close(pipeFds[0]);
    return "cannot start " + argv[0] + ": " + std::strerror(spawned);
  }
  const std::string last = teeLastLine(pipeFds[0]);
  close(pipeFds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (ok) return "";
  return last.empty() ? exitProblem(status) : last + " (" + exitProblem(status) + ")";
}

}  // namespace

BatchResult runBatchJob(const BatchJob& job, const std::filesystem::path& program) {
  BatchResult result{.job = job.index, .kind = job.kind, .ok = false, .output = job.output, .error = job.error};
  if (!job.error.empty()) return result;
  const auto start = std::chrono::steady_clock::now();
  result.error = spawnAndWait(job, program, result.ok);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

eng::Result<BatchSummary> runBatch(const std::vector<BatchJob>& jobs, const BatchOptions& options) {
  BatchSummary summary;
  std::string lines;
  for (const BatchJob& job : jobs) {
    if (!options.shard.owns(job.index)) continue;
    BatchResult result = runBatchJob(job, options.program);
    const std::string line = resultJson(result) + "\n";
    if (options.echo) std::fputs(line.c_str(), options.echo), std::fflush(options.echo);
    lines += line;
    if (!options.results.empty())
      ENG_TRY(eng::writeFileWhole(options.results, [&](const std::filesystem::path& partial) {
        return eng::writeFileBytes(partial, lines.data(), lines.size());
      }));
    summary.failed += result.ok ? 0 : 1;
    summary.results.push_back(std::move(result));
  }
  return summary;
}

}  // namespace dataset
