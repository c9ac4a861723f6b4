#include "coupling/studies/plot_script.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <string>

extern char** environ;

namespace upgrain::coupling {

bool run_plot_script(const std::filesystem::path& script, const std::filesystem::path& folder,
                     const std::filesystem::path& log) {
  static const std::filesystem::path python = "/usr/bin/python3";
  std::error_code ec;
  if (!std::filesystem::exists(script, ec) || !std::filesystem::exists(python, ec)) return false;
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  // Blocked signals stay blocked across exec: the stop signals wait, undelivered, until the
  // script has ended.
  sigset_t stop;
  sigemptyset(&stop);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stop, s);
  posix_spawnattr_setsigmask(&attributes, &stop);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  std::string a0 = python.string(), a1 = script.string(), a2 = folder.string();
  char* argv[] = {a0.data(), a1.data(), a2.data(), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, a0.c_str(), &files, &attributes, argv, environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return false;
  int status = 0;
  // A stop signal interrupts the wait (the handlers are installed without SA_RESTART).
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return false;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace upgrain::coupling
