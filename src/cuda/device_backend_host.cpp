// The "host" build of the device back end: device_backend.cu compiled by g++ against CCCL with Thrust's
// OpenMP device system, so every machine runs (and tests) the device code on its CPU cores.
#include <sys/auxv.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#define SPH_DEVICE_NS host_device
#define SPH_DEVICE_FACTORY make_host_backend
#define SPH_DEVICE_NAME "host"
#define SPH_DEVICE_PREPARE() ((void)0)
#include "device_backend.cu"

namespace {

// OpenMP threads waiting at a barrier spin by default (libgomp: 300,000 spins, a few milliseconds) before
// they sleep. A step runs dozens of parallel loops, so where the cores also run other work the spinning
// threads take the time slices the working ones need: on 2 shared cores the dam break ran 25 times slower
// on host than on the serial cpu back end (issue 10, item 9). A short spin, GOMP_SPINCOUNT = 1,000, keeps
// both cases fast. Dam break, host ms/step on 2 cores, passive (no spin) / 1,000 / 10,000 spins / libgomp's
// default: idle, 16k particles 5.6 / 4.4 / 4.4 / 4.1 and 2k particles 1.68 / 0.65 / 0.55 / 0.65; beside two
// busy processes, 16k 11.8-13.4 / 8.1-10.4 / 8.2-8.4 (cpu 7.9), and with a third, 20 / 23 / 53 / 298-866
// (cpu 53-65); beside two niced processes 9.5 / 10.4-11.2 / 23.6. Passive costs a wake-up per loop (2.6
// times slower on small scenes when idle); 10,000 spins can double the step under load; 1,000 stays
// within 1.2 times the better of the two everywhere measured.
//
// libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, in its constructor, before main. The executable's
// .preinit_array runs before any library's constructor, but a setenv() there is lost: libc's own
// initialisation, which comes next, points `environ` back at the process's original environment. So, when
// the user has set neither variable, the program executes itself again with GOMP_SPINCOUNT=1000 added
// (about a millisecond); the second start finds the variable and goes on. If that exec fails (no /proc),
// the program runs on with libgomp's default, as it does when started through the dynamic loader by hand
// (`ld.so PROGRAM`, AT_BASE 0), where /proc/self/exe is the loader. This object is linked into every
// executable that can create the host back end: it holds make_host_backend.
void prefer_short_omp_spinning(int, char** argv, char** envp) {
  if (getauxval(AT_BASE) == 0) return;
  std::size_t n = 0;
  for (; envp[n]; ++n)
    if (!std::strncmp(envp[n], "OMP_WAIT_POLICY=", 16) || !std::strncmp(envp[n], "GOMP_SPINCOUNT=", 15)) return;
  char** with_policy = static_cast<char**>(std::malloc((n + 2) * sizeof(char*)));
  if (!with_policy) return;
  static char short_spin[] = "GOMP_SPINCOUNT=1000";
  std::memcpy(with_policy, envp, n * sizeof(char*));
  with_policy[n] = short_spin;
  with_policy[n + 1] = nullptr;
  execve("/proc/self/exe", argv, with_policy);
  std::free(with_policy);  // only reached when the exec failed
}

__attribute__((section(".preinit_array"), used)) void (*const sph_short_omp_spinning)(int, char**, char**) =
    prefer_short_omp_spinning;

}  // namespace
