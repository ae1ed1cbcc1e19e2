// Continuing a run from a frame (sph_run --restart, the scene key "initial_state") and atomic frames.
// A continued run must give the same bits as the uninterrupted one, particle by particle, on every back
// end; frames that cannot be trusted are refused; a failed write leaves no partial file.
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <catch2/catch.hpp>

#include "app/backends.h"
#include "common/frame_reader.h"
#include "common/frame_writer.h"
#include "physics_helpers.h"

using namespace sph_test;
namespace fs = std::filesystem;

namespace {

// A fresh, empty folder for one test's files, removed with everything in it at the end of the test.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name)
      : dir(fs::temp_directory_path() / ("sph_test_restart_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Particles (by id) whose state differs in any bit of any stored field (motion_only: of position,
// velocity, age and fluid, the fields a run started from a frame takes over unchanged).
long differing_particles(const sph::ParticleState& a, const sph::ParticleState& b, bool motion_only = false) {
  std::map<int32_t, std::size_t> in_b;
  for (std::size_t j = 0; j < b.size(); ++j) in_b[b.id[j]] = j;
  long differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto it = in_b.find(a.id[i]);
    if (it == in_b.end()) {
      ++differ;
      continue;
    }
    const std::size_t j = it->second;
    const bool motion = same_bits(a.pos[i], b.pos[j]) && same_bits(a.vel[i], b.vel[j]) &&
                        same_bits(a.age[i], b.age[j]) && a.fluid[i] == b.fluid[j];
    const bool same = motion && (motion_only || (same_bits(a.acc[i], b.acc[j]) && same_bits(a.density[i], b.density[j]) &&
                                                 same_bits(a.pressure[i], b.pressure[j])));
    if (!same) ++differ;
  }
  return differ;
}

struct Continued {
  sph::ParticleState uninterrupted, continued;
  double time_uninterrupted = 0.0, time_continued = 0.0;
  int32_t next_id_uninterrupted = 0, next_id_continued = 0;
  double budget_uninterrupted = 0.0, budget_continued = 0.0;  // the energy check's budget [J]
};

// Runs `total` steps in one go, and again as `at` steps, a frame, and a continuation from that frame read
// back from disk. edit_frame may change the frame before the continuation (to show the check can fail).
template <class Edit>
Continued run_and_continue(const sph::Scene& scene, const sph::BackendFactory& factory, long at, long total,
                           const fs::path& dir, Edit edit_frame) {
  Continued r;
  sph::Simulation whole(scene, factory, 1.0);
  while (whole.steps() < total) whole.advance();
  r.uninterrupted = whole.particles();
  r.time_uninterrupted = whole.time();
  r.next_id_uninterrupted = whole.frame_info(0).next_id;
  r.budget_uninterrupted = whole.energy_budget();

  const std::string path = (dir / "frame_00003.ply").string();
  {
    sph::Simulation first(scene, factory, 1.0);
    while (first.steps() < at) first.advance();
    sph::write_ply_frame(path, first.particles(), first.frame_info(3));
  }
  sph::Frame frame = sph::read_ply_frame(path, scene.max_particles);
  edit_frame(frame);
  sph::Simulation rest(scene, factory, 1.0, &frame);
  REQUIRE(rest.steps() == at);
  while (rest.steps() < total) rest.advance();
  r.continued = rest.particles();
  r.time_continued = rest.time();
  r.next_id_continued = rest.frame_info(4).next_id;
  r.budget_continued = rest.energy_budget();
  return r;
}

void require_identical(const Continued& r) {
  REQUIRE(r.continued.size() == r.uninterrupted.size());
  CHECK(same_bits(r.time_continued, r.time_uninterrupted));
  CHECK(r.next_id_continued == r.next_id_uninterrupted);
  // The blow-up check of the continued run uses the original run's budget (with the jets' energy put in),
  // not one re-based on the frame's state, so it stops where the uninterrupted run would.
  CHECK(same_bits(r.budget_continued, r.budget_uninterrupted));
  CHECK(differing_particles(r.uninterrupted, r.continued) == 0);
}

const auto keep_frame = [](sph::Frame&) {};

std::vector<std::string> backends_to_test() {
  std::vector<std::string> names{"cpu"};
  for (const std::string& b : sph::available_backends())
    if (b == "host") names.push_back(b);
  return names;
}

}  // namespace

TEST_CASE("a dam break continued from a frame gives the same bits as the uninterrupted run", "[restart]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=8"});
  for (const std::string& backend : backends_to_test()) {
    INFO("back end " << backend);
    const Continued r = run_and_continue(scene, sph::backend_factory(backend), 15, 40, Scratch("dam_" + backend).dir, keep_frame);
    require_identical(r);
    CHECK(r.uninterrupted.size() == 1024);  // 8 x 16 x 8
  }
}

TEST_CASE("DFSPH and PBF runs continued from a frame give the same bits as the uninterrupted runs", "[restart]") {
  // DFSPH warm-starts from the pressures the last step ended with (src/solvers/dfsph.h): the frame carries
  // both, pressure and near_pressure (without near_pressure the continuation differed after one step).
  for (const std::vector<std::string>& sets : {std::vector<std::string>{"solver=dfsph"},
                                               std::vector<std::string>{"solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004"}}) {
    std::vector<std::string> all{"resolution.particles_across=8"};
    all.insert(all.end(), sets.begin(), sets.end());
    const sph::Scene scene = scene_file("dam_break.json", all);
    for (const std::string& backend : backends_to_test()) {
      INFO(sets[0] << ", back end " << backend);
      const Continued r = run_and_continue(scene, sph::backend_factory(backend), 10, 25,
                                           Scratch(sets[0].substr(7) + "_" + backend).dir, keep_frame);
      require_identical(r);
    }
  }
}

TEST_CASE("a jet continued from a frame emits the same particles at the same steps", "[restart]") {
  // Low resolution: about 4 particles across the jet, a layer every 10.5 steps; the frame falls between
  // two layers, so the emission accumulator matters.
  const sph::Scene scene = scene_file("water_jet.json", {"resolution.particles_across=4"});
  for (const std::string& backend : backends_to_test()) {
    INFO("back end " << backend);
    const Continued r = run_and_continue(scene, sph::backend_factory(backend), 33, 90, Scratch("jet_" + backend).dir, keep_frame);
    require_identical(r);
    CHECK(r.next_id_uninterrupted > 150);  // layers were emitted after the frame
  }
}

TEST_CASE("the comparison sees a continuation that does not restore the state exactly", "[restart]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=8"});
  // Without the stored accelerations the first continued step differs, and so does everything after it.
  const Continued no_acc = run_and_continue(scene, cpu_factory(), 15, 20, Scratch("no_acc").dir, [](sph::Frame& f) {
    for (sph::Vec3& a : f.particles.acc) a = sph::Vec3{0.0f, 0.0f, 0.0f};
  });
  CHECK(differing_particles(no_acc.uninterrupted, no_acc.continued) > 900);
  // Without the jets' emission accumulators the next layers are born at other places.
  const sph::Scene jet = scene_file("water_jet.json", {"resolution.particles_across=4"});
  const Continued no_acc_jet = run_and_continue(jet, cpu_factory(), 33, 60, Scratch("no_travelled").dir, [](sph::Frame& f) {
    for (double& t : f.info.jet_travelled) t = 0.0;
  });
  CHECK(differing_particles(no_acc_jet.uninterrupted, no_acc_jet.continued) > 0);
}

TEST_CASE("a frame stores the run's time, step, next id, jet accumulators and scene exactly", "[restart]") {
  const Scratch scratch("header");
  const fs::path& dir = scratch.dir;
  const sph::Scene scene = scene_file("water_jet.json", {"resolution.particles_across=4"});
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  while (sim.steps() < 27) sim.advance();
  const std::string path = (dir / "f.ply").string();
  sph::write_ply_frame(path, sim.particles(), sim.frame_info(7));
  const sph::Frame f = sph::read_ply_frame(path, scene.max_particles);
  CHECK(same_bits(f.info.time, sim.time()));
  CHECK(f.info.step == 27);
  CHECK(f.info.frame_index == 7);
  CHECK(f.info.scene == "water_jet");
  CHECK(same_bits(f.info.spacing, sim.setup().spacing));
  REQUIRE(f.info.jet_travelled.size() == 1);
  CHECK(same_bits(f.info.jet_travelled[0], sim.setup().jets[0].travelled()));
  CHECK(f.info.jet_travelled[0] > 0.0);
  CHECK(f.info.next_id == sim.setup().next_id);
  CHECK(differing_particles(sim.particles(), f.particles) == 0);
  CHECK_FALSE(fs::exists(path + ".tmp"));
}

TEST_CASE("a scene can start from a frame (initial_state)", "[restart]") {
  const Scratch scratch("initial_state");
  const fs::path& dir = scratch.dir;
  const sph::Scene dam = scene_file("dam_break.json", {"resolution.particles_across=8"});
  sph::Simulation source(dam, cpu_factory(), 1.0);
  while (source.steps() < 20) source.advance();
  sph::write_ply_frame((dir / "start.ply").string(), source.particles(), source.frame_info(0));

  // The scene file names the frame relative to its own folder; a jet still runs.
  std::ifstream in(std::string(SPH_SOURCE_DIR) + "/scenes/dam_break.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string scene_path = (dir / "from_frame.json").string();
  const std::vector<std::string> with_jet{
      "initial_state=start.ply", "resolution.particles_across=8",
      R"(emitters=[{"type": "box", "min": [0, 0, 0], "max": [0.05715, 0.1143, 0.05715]},
                   {"type": "jet", "position": [0.3, 0.15, 0.028], "direction": [0, -1, 0], "radius": 0.01, "speed": 1}])"};
  const sph::Scene scene = sph::parse_scene(text, scene_path, with_jet);
  CHECK(scene.initial_state == (dir / "start.ply").string());
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  CHECK(sim.time() == 0.0);
  CHECK(sim.steps() == 0);
  // The frame's particles (the box's 1024, moved for 20 steps) replace the box's fill ...
  const sph::ParticleState moved = source.particles();
  const sph::ParticleState start = sim.particles();
  REQUIRE(start.size() > moved.size());
  const std::size_t inlet = start.size() - moved.size();  // ... and the jet prefilled its inlet with new ids
  sph::ParticleState from_frame;
  for (std::size_t i = 0; i < start.size(); ++i)
    if (start.id[i] < int32_t(moved.size())) {
      const std::size_t k = from_frame.size();
      from_frame.resize(k + 1);
      from_frame.copy_particle(k, start, i);
    }
  REQUIRE(from_frame.size() == moved.size());
  CHECK(differing_particles(moved, from_frame, true) == 0);
  while (sim.steps() < 30) sim.advance();
  CHECK(sim.frame_info(0).next_id > int32_t(moved.size() + inlet));  // the jet emitted on

  // Another spacing would give the particles other masses: refused, naming the key and both spacings.
  std::vector<std::string> finer = with_jet;
  finer[1] = "resolution.particles_across=9";
  try {
    sph::Simulation wrong(sph::parse_scene(text, scene_path, finer), cpu_factory(), 1.0);
    FAIL("a frame of another spacing was accepted");
  } catch (const sph::SceneError& e) {
    const std::string msg = e.what();
    INFO(msg);
    CHECK(msg.find("initial_state") != std::string::npos);
    CHECK(msg.find("start.ply") != std::string::npos);
    CHECK(msg.find("spacing") != std::string::npos);
  }
}

TEST_CASE("a scene that starts from a frame needs no emitter, but then a spacing", "[restart]") {
  const Scratch scratch("no_emitters");
  const sph::Scene dam = scene_file("dam_break.json", {"resolution.particles_across=8"});
  sph::Simulation source(dam, cpu_factory(), 1.0);
  sph::write_ply_frame((scratch.dir / "start.ply").string(), source.particles(), source.frame_info(0));
  const std::string scene_path = (scratch.dir / "scene.json").string();
  auto scene_with = [&](const std::string& resolution) {
    return sph::parse_scene(R"({ "name": "from_frame", "fluids": [ { "speed_of_sound": 20 } ],
      "initial_state": "start.ply", "resolution": )" + resolution + R"(,
      "boundaries": [ { "type": "box", "min": [0, 0, 0], "max": [0.4572, 0.2286, 0.05715] } ] })",
                            scene_path);
  };
  sph::Simulation sim(scene_with(R"({ "spacing": 0.00714375 })"), cpu_factory(), 1.0);
  CHECK(sim.particles().size() == source.particles().size());
  try {
    scene_with(R"({ "particles_across": 8 })");
    FAIL("particles_across without an emitter was accepted");
  } catch (const sph::SceneError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("resolution.particles_across") != std::string::npos);
    CHECK(std::string(e.what()).find("resolution.spacing") != std::string::npos);
  }
}

namespace {

// The refusal message for a frame file, or "" when it was accepted.
std::string refusal(const std::string& path, const sph::Scene& scene) {
  try {
    const sph::Frame f = sph::read_ply_frame(path, scene.max_particles);
    sph::check_frame_fluids(f, scene, path);
  } catch (const sph::SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("frames that cannot be trusted are refused with a message naming the file", "[restart]") {
  const Scratch scratch("bad");
  const fs::path& dir = scratch.dir;
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=8"});
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  sim.advance();
  const sph::ParticleState good = sim.particles();
  const std::string path = (dir / "frame.ply").string();
  auto write = [&](const sph::ParticleState& ps) { sph::write_ply_frame(path, ps, sim.frame_info(1)); };
  auto refused_for = [&](const std::string& why) {
    const std::string msg = refusal(path, scene);
    INFO("message: " << msg);
    CHECK(msg.find(path) != std::string::npos);
    CHECK(msg.find(why) != std::string::npos);
  };

  write(good);
  CHECK(refusal(path, scene).empty());

  SECTION("truncated in the records") {
    fs::resize_file(path, fs::file_size(path) - 10);
    refused_for("truncated");
  }
  SECTION("truncated in the header") {
    fs::resize_file(path, 200);
    refused_for("end_header");
  }
  SECTION("longer than its records") {
    std::ofstream(path, std::ios::app | std::ios::binary) << "xyz";
    refused_for("bytes follow");
  }
  SECTION("missing") {
    fs::remove(path);
    refused_for("no such frame file");
  }
  SECTION("not a frame") {
    std::ofstream(path) << "{\"name\": \"a scene, not a frame\"}\n";
    refused_for("not a PLY file");
  }
  SECTION("an older frame without acceleration, age and near pressure") {
    std::ofstream(path, std::ios::binary) << "ply\nformat binary_little_endian 1.0\ncomment sph frame, time 0.1 s\n"
                                             "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                                             "property float vx\nproperty float vy\nproperty float vz\n"
                                             "property float density\nproperty float pressure\nproperty uchar fluid\n"
                                             "property int id\nend_header\n";
    refused_for("ax ay az age");
  }
  SECTION("a fluid the scene does not have") {
    sph::ParticleState ps = good;
    ps.fluid[3] = 1;
    write(ps);
    refused_for("fluid 1");
  }
  SECTION("a non-finite value") {
    sph::ParticleState ps = good;
    ps.vel[5].y = std::nanf("");
    write(ps);
    refused_for("non-finite velocity");
  }
  SECTION("a repeated id") {
    sph::ParticleState ps = good;
    ps.id[7] = ps.id[8];
    write(ps);
    refused_for("more than once");
  }
  SECTION("more particles than limits.max_particles") {
    const sph::Scene small = scene_file("dam_break.json", {"resolution.particles_across=8", "limits.max_particles=100"});
    const std::string msg = refusal(path, small);
    CHECK(msg.find("limits.max_particles") != std::string::npos);
  }
}

TEST_CASE("a frame continues only the scene, resolution and solver that wrote it", "[restart]") {
  const Scratch scratch("mismatch");
  const fs::path& dir = scratch.dir;
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=8"});
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  sim.advance();
  const std::string path = (dir / "frame.ply").string();
  sph::write_ply_frame(path, sim.particles(), sim.frame_info(1));
  const sph::Frame frame = sph::read_ply_frame(path, scene.max_particles);
  auto refused = [&](const sph::Scene& other, const std::string& why) {
    try {
      sph::Simulation continued(other, cpu_factory(), 1.0, &frame);
      FAIL("continued " << other.source << " from a frame of another run");
    } catch (const sph::SceneError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find(path) != std::string::npos);
      CHECK(msg.find(why) != std::string::npos);
    }
  };
  refused(scene_file("dam_break.json", {"resolution.particles_across=9"}), "spacing");
  refused(scene_file("hydrostatic_tank.json", {}), "hydrostatic");
  // The solvers keep different state in the same fields: the frame names its solver.
  refused(scene_file("dam_break.json", {"resolution.particles_across=8", "solver=dfsph"}), "solver \"wcsph\"");
}

TEST_CASE("a frame write that fails leaves no partial file", "[restart]") {
  const Scratch scratch("atomic");
  const fs::path& dir = scratch.dir;
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=8"});
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  const std::string path = (dir / "frame_00001.ply").string();

  SECTION("the folder does not exist") {
    const std::string missing = (dir / "no_such_folder" / "frame.ply").string();
    try {
      sph::write_ply_frame(missing, sim.particles(), sim.frame_info(1));
      FAIL("the write into a missing folder did not fail");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()).find(missing) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(missing));
  }

  SECTION("the disk fills up in the middle of the frame") {
    // An older complete frame of that name must survive a failed rewrite untouched.
    sph::write_ply_frame(path, sim.particles(), sim.frame_info(1));
    const auto old_size = fs::file_size(path);
    REQUIRE(old_size > 50000);
    // A file size limit below the frame's size: write() fails with EFBIG part way, as on a full disk.
    rlimit saved{};
    REQUIRE(getrlimit(RLIMIT_FSIZE, &saved) == 0);
    const sighandler_t saved_handler = signal(SIGXFSZ, SIG_IGN);
    rlimit small = saved;
    small.rlim_cur = 20000;
    REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
    std::string message;
    try {
      sim.advance();
      sph::write_ply_frame(path, sim.particles(), sim.frame_info(2));
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    setrlimit(RLIMIT_FSIZE, &saved);
    signal(SIGXFSZ, saved_handler);
    INFO("message: " << message);
    CHECK(message.find(path) != std::string::npos);
    CHECK(fs::file_size(path) == old_size);
    CHECK(sph::read_ply_frame(path, scene.max_particles).info.frame_index == 1);  // the old frame, whole
    CHECK_FALSE(fs::exists(path + ".tmp"));
  }
}
