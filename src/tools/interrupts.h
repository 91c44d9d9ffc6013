// SIGINT and SIGTERM end a command cleanly: its unfinished output is removed and one line says so.
//
// The signals are blocked in every thread and one thread waits for them (sigwait), so the clean-up
// runs as ordinary code, not in a signal handler where removing a folder is not allowed. On a
// signal it kills the child processes registered here (ffmpeg), removes the temporary files and
// folders registered here, prints "haif CMD: interrupted (SIGINT): ..." and exits with 128 + the
// signal number. The output of a finished run is never registered, so it is never touched.
#pragma once

#include <sys/types.h>

#include <string>

namespace haif {

/// Blocks SIGINT and SIGTERM in the calling thread, and so in every thread it starts afterwards:
/// call it first thing in main. `command` names the command in the line printed on a signal.
void installInterruptHandler(const std::string& command);

/// A temporary file or folder to remove if the command is interrupted before it is released.
void registerTemporary(const std::string& path);
void releaseTemporary(const std::string& path);

/// A child process to kill (and wait for) if the command is interrupted.
void registerChild(pid_t pid);
void releaseChild(pid_t pid);

/// In a child after fork(), before exec: unblocks the two signals, so the program it runs can be
/// stopped (the blocked mask is inherited across exec).
void unblockInterruptsInChild();

/// Does not return while an interrupt is being handled (the handler's thread ends the process):
/// called before printing an error, it keeps a failure caused by the clean-up (a frame that could
/// not be written into a removed folder) from printing a second, misleading line.
void waitIfInterrupted();

}  // namespace haif
