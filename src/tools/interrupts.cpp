#include "tools/interrupts.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

namespace haif {

namespace {

std::mutex mutex;
std::set<std::string> temporaries;
std::set<pid_t> children;
std::string commandName = "haif";
std::atomic<bool> interrupting{false};

sigset_t interruptSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

[[noreturn]] void handle(int sig) {
  interrupting = true;
  std::lock_guard<std::mutex> lock(mutex);  // held until _exit: nothing registers or releases meanwhile
  // Children first: an ffmpeg still writing would recreate its file after it was removed.
  for (const pid_t pid : children) {
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  size_t removed = 0;
  for (const std::string& path : temporaries) {
    std::error_code ec;
    // Another thread may still be writing a file into a folder: remove until it is gone.
    for (int attempt = 0; attempt < 5 && std::filesystem::symlink_status(path, ec).type() !=
                                             std::filesystem::file_type::not_found;
         ++attempt)
      std::filesystem::remove_all(path, ec);
    ++removed;
  }
  const std::string line = commandName + ": interrupted (" + (sig == SIGINT ? "SIGINT" : "SIGTERM") +
                           "): stopped before it finished; " +
                           (removed ? "its unfinished output was removed" : "nothing was written") + "\n";
  // On a terminal the progress line is rewritten in place (tools/progress.h): clear it first.
  const std::string text = (::isatty(STDERR_FILENO) ? "\r\033[K" : "") + line;
  if (::write(STDERR_FILENO, text.data(), text.size()) < 0) { /* nothing left to tell */ }
  ::_exit(128 + sig);
}

}  // namespace

void installInterruptHandler(const std::string& command) {
  commandName = command;
  const sigset_t set = interruptSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    handle(sig);
  }).detach();
}

void registerTemporary(const std::string& path) {
  std::lock_guard<std::mutex> lock(mutex);
  temporaries.insert(path);
}

void releaseTemporary(const std::string& path) {
  std::lock_guard<std::mutex> lock(mutex);
  temporaries.erase(path);
}

void registerChild(pid_t pid) {
  std::lock_guard<std::mutex> lock(mutex);
  children.insert(pid);
}

void releaseChild(pid_t pid) {
  std::lock_guard<std::mutex> lock(mutex);
  children.erase(pid);
}

void unblockInterruptsInChild() {
  const sigset_t set = interruptSignals();
  sigprocmask(SIG_UNBLOCK, &set, nullptr);
}

void waitIfInterrupted() {
  if (!interrupting) return;
  for (;;) ::pause();
}

}  // namespace haif
