#include <membrane/solvers/blas_threads.h>

#include <cstdlib>
#include <dlfcn.h>

namespace Membrane
{
  void use_single_threaded_blas()
  {
    if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr)
      return;
    using SetThreads = void (*)(int);
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
      set(1);
  }
} // namespace Membrane
