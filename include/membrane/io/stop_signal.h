#pragma once
// Graceful stop on SIGTERM / SIGINT (Ctrl-C, a batch system's time limit, a sweep that
// is stopped). The handlers only record the signal in an atomic flag; the time loop
// polls stop_requested() between steps, stops, writes its final state (statistics,
// checkpoint, summary with the stop reason) and the program exits with 128 + signal
// (130 for SIGINT, 143 for SIGTERM), so a sweep sees the case as interrupted.
//
// Until something polls the flag (the first call of stop_requested()), nobody would act
// on it, so a signal keeps its default action and ends the process at once (exit by
// the signal, as without handlers). A second signal after the flag is set always ends
// the process at once (press Ctrl-C twice to abort a step that takes long).
//
// Under MPI each rank gets the signal from mpirun; the ranks must agree on when to
// stop: reduce the flag over the communicator (e.g. Utilities::MPI::max of
// int(stop_requested())) at the same point of the loop on every rank.

namespace Membrane
{
  /// Installs the SIGTERM and SIGINT handlers (idempotent; async-signal-safe handlers).
  void install_stop_signal_handlers();

  /// True once SIGTERM or SIGINT has arrived after install_stop_signal_handlers().
  /// The first call also tells the handlers that the flag is being polled (see above).
  bool stop_requested();

  /// The signal that requested the stop (SIGTERM, SIGINT), 0 if none.
  int stop_signal();

  /// Name of a signal for messages ("SIGTERM", "SIGINT", otherwise "signal N").
  const char *stop_signal_name(int signal);

  /// For tests: forget a recorded signal (the handlers stay installed).
  void reset_stop_request();
} // namespace Membrane
