// SPDX-License-Identifier: MIT
// SIGINT/SIGTERM for silkgen and silktok: Slurm's time limit, scancel, `timeout` and Ctrl-C end a
// run within a second and leave no temporary file (libsilk's silk_file_discard_partial), whatever
// the process is doing. A blocked system call is interrupted, not restarted.
#pragma once

namespace silkapp {

enum class OnInterrupt {
  kCancel,  // first signal: recorded (InterruptSignal), the work polls it and stops; a second one, or
            // a second passing (POSIX), ends the process
  kExit,    // first signal ends the process (no cancel points)
};

// Installs the handlers for SIGINT and SIGTERM (SIGINT and SIGBREAK on Windows). Ending the
// process: the temporaries of writes in progress are removed, then the signal's default action
// (exit status 128 + signal).
void HandleInterrupts(OnInterrupt mode);
// The signal received (kCancel mode), 0 if none. Async-signal-safe to read.
int InterruptSignal();

}  // namespace silkapp
