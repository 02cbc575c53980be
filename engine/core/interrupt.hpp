// A run is stopped cleanly by SIGINT or SIGTERM: the first signal only sets a flag that the time loop reads
// between steps, so the step in progress ends, the frame being written is finished, run.json, timings.json
// and (if enabled) a checkpoint are written and the program exits with 128 + the signal number. A second
// signal restores the default action and so stops the program at once.
#pragma once

namespace loom {

// Installs the handlers of SIGINT and SIGTERM (the program calls it once, before a run).
void install_interrupt_handlers();
// True once a handled signal arrived (or request_interrupt was called).
bool interrupt_requested();
// The signal that asked to stop (SIGINT, SIGTERM), 0 if none.
int interrupt_signal();
// As if `signal` had arrived (tests); clear_interrupt() forgets it.
void request_interrupt(int signal);
// Across the ranks of `mpirun -n N loom run` a signal reaches each rank at its own moment, and the ranks must stop
// after the same step (every step's solve is collective): with an agreement set (a collective maximum over the
// ranks), the time loop stops when any rank was signalled. Null: this process decides alone.
void set_interrupt_agreement(int (*agree)(int local_signal));
// The signal that ends the run before the next step (0: none): this process's, or the ranks' agreed one.
int agreed_interrupt_signal();
void clear_interrupt();
const char* signal_name(int signal);

}  // namespace loom
