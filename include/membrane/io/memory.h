#pragma once
// The memory of the machine(s) a run has, and what the run itself uses: the start-up
// check of the mesh size (app.cc, estimate_memory() in parameters.h) and the check before
// each local refinement (Simulator::adapt_mesh) read them.
#include <mpi.h>

#include <string>

namespace Membrane
{
  /// MemAvailable of /proc/meminfo in bytes (negative if unknown).
  double host_available_memory();

  /// MemAvailable summed over the distinct hosts of the ranks (negative if unknown on
  /// any). Collective; every rank gets the same value.
  double available_memory(MPI_Comm communicator);

  /// Resident memory (VmRSS of /proc/self/status) of this process in bytes (negative if unknown).
  double resident_memory();

  /// "271.0 MB", "1.7 GB", "3.2 TB".
  std::string format_bytes(double bytes);
} // namespace Membrane
