#include <membrane/io/stop_signal.h>

#include <atomic>
#include <csignal>
#include <initializer_list>
#include <cstdio>

#include <signal.h>

namespace Membrane
{
  namespace
  {
    static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
                  "signal handlers need lock-free atomics");

    std::atomic<int>  requested_signal{0};
    std::atomic<bool> polled{false};
    std::atomic<bool> installed{false};

    /// Restore the default action and raise the signal again: the process ends as if
    /// no handler had been installed (async-signal-safe: sigaction, raise).
    void end_by_default_action(const int signal)
    {
      struct sigaction action = {};
      action.sa_handler       = SIG_DFL;
      sigemptyset(&action.sa_mask);
      sigaction(signal, &action, nullptr);
      raise(signal);
    }

    extern "C" void on_stop_signal(const int signal)
    {
      if (!polled.load() || requested_signal.load() != 0)
        {
          end_by_default_action(signal);
          return;
        }
      requested_signal.store(signal);
    }
  } // namespace

  void install_stop_signal_handlers()
  {
    if (installed.exchange(true))
      return;
    struct sigaction action = {};
    action.sa_handler       = on_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART; // blocking calls (file writes, MPI) continue after the handler
    for (const int signal : {SIGTERM, SIGINT})
      sigaction(signal, &action, nullptr);
  }

  bool stop_requested()
  {
    polled.store(true);
    return requested_signal.load() != 0;
  }

  int stop_signal()
  {
    return requested_signal.load();
  }

  const char *stop_signal_name(const int signal)
  {
    switch (signal)
      {
        case SIGTERM: return "SIGTERM";
        case SIGINT: return "SIGINT";
        case SIGHUP: return "SIGHUP";
        case SIGQUIT: return "SIGQUIT";
        default:
          {
            thread_local char buffer[24];
            std::snprintf(buffer, sizeof buffer, "signal %d", signal);
            return buffer;
          }
      }
  }

  void reset_stop_request()
  {
    requested_signal.store(0);
  }
} // namespace Membrane
