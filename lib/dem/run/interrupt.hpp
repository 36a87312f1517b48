#pragma once
// SIGINT / SIGTERM: the handler only records the signal; a run checks it after every step, stops,
// and writes everything (series, snapshots, summary with status "interrupted", a checkpoint).
namespace dem {

/// Installs the handlers for SIGINT and SIGTERM (the command line does this; library users may not).
void install_interrupt_handlers();
/// The signal received (SIGINT or SIGTERM), or 0.
int interrupt_signal();
/// Records `sig` as if it had been received (tests); 0 clears it.
void set_interrupt_signal(int sig);

}  // namespace dem
