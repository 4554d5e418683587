#pragma once
// OpenBLAS starts one busy-waiting thread per core. Next to MPI ranks and the
// sparse direct solver that oversubscribes the machine (measured: a shape-step
// run took 2.8x longer, most of it in the kernel). Unless the user chose a
// count with OPENBLAS_NUM_THREADS, the library is set to one thread per process.

namespace Membrane
{
  /// Calls openblas_set_num_threads(1) if OpenBLAS is the loaded BLAS and the
  /// environment does not set OPENBLAS_NUM_THREADS; does nothing otherwise.
  void use_single_threaded_blas();
} // namespace Membrane
