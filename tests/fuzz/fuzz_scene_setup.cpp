// libFuzzer target: a scene file's bytes through the whole set-up a run goes through before its first
// step (parse and validate, guided creation, load-time checks, grid, back end, initial forces), and, when
// the scene is small, a few steps of the serial reference. Anything may be refused with SceneError or
// BlowUp; a crash, a sanitizer finding, an uncaught exception, a hang (-timeout) or an allocation above
// -malloc_limit_mb is a finding. Built with clang by tests/fuzz/run_fuzz.sh (see CMakeLists.txt beside it).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <string>

#include "common/scene.h"
#include "common/simulation.h"
#include "cpu/cpu_backend.h"

namespace {

// Keeps one input cheap: a fuzzer needs thousands of executions, and the budget checks it exercises are
// the same whatever the limit is.
constexpr double kFuzzMaxParticles = 20000.0;
constexpr std::size_t kStepParticles = 2000;  // small scenes also run a few steps

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    sph::Scene scene = sph::parse_scene(text, "fuzz.json");
    if (scene.max_particles > kFuzzMaxParticles) scene.max_particles = kFuzzMaxParticles;
    const sph::BackendFactory cpu = [](const sph::SimConstants& c) { return std::make_unique<sph::CpuBackend>(c); };
    sph::Simulation sim(scene, cpu, scene.run_time);
    if (sim.backend().size() <= kStepParticles)
      for (int i = 0; i < 3; ++i) sim.advance();
  } catch (const sph::SceneError&) {  // refused with a message: the expected answer to a bad scene
  } catch (const sph::BlowUp&) {      // an unstable scene reported as such
  }
  return 0;
}
