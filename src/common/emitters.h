// Emitters (thesis 4.1.4): instant box and sphere fills on ONE cubic lattice shared by every instant
// emitter, and continuous jets with a circular or square section that are fed through an inlet region
// (thesis 4.1.6).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "particle_state.h"
#include "scene.h"

namespace sph {

// The cubic lattice of spacing d [m] on which every instant emitter is filled: point (i, j, k) lies at
// origin + (i, j, k) d. One lattice for all emitters means that overlapping or touching emitters share
// lattice points instead of creating particles on top of each other.
struct Lattice {
  Vec3d origin{};
  double spacing = 0.0;
  Vec3d point(long i, long j, long k) const {
    return {origin[0] + double(i) * spacing, origin[1] + double(j) * spacing, origin[2] + double(k) * spacing};
  }
};

// Anchored so that the first layer lies half a spacing inside the walls: at the min corner of the first
// box container plus d/2, or, without one, at the first instant emitter's min corner plus d/2.
Lattice make_lattice(const Scene& scene, double spacing);

// Inclusive index ranges [lo, hi] per axis (empty when hi < lo on an axis).
struct IndexBox {
  long lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};
  double count() const;  // number of index triples, as a double (no overflow)
};

// Lattice indices an instant emitter may hold, from its bounding box alone; no allocation, so the
// particle budget can be checked on count() before anything is built.
IndexBox emitter_index_box(const EmitterSpec& e, const Lattice& lattice);

// The lattice points of one instant emitter. A box holds the points whose lattice cell centre lies in
// [min, max) on every axis, so its filled extent differs from the asked one by less than one spacing
// and two boxes that touch never share a layer. A sphere holds the points strictly inside its radius that
// keep at least 3 of their 6 lattice neighbours in the fill (no single particles at the poles).
class EmitterRegion {
 public:
  EmitterRegion(const EmitterSpec& e, const Lattice& lattice);
  const IndexBox& box() const { return box_; }
  bool contains(long i, long j, long k) const;

 private:
  std::size_t mask_index(long i, long j, long k) const;
  bool strictly_inside(long i, long j, long k) const;

  EmitterSpec spec_;
  Lattice lattice_;
  IndexBox box_;
  std::vector<uint8_t> mask_;  // sphere: 1 for points in the fill, over box_ (x fastest)
};

// One filled lattice point and the instant emitter (index into scene.emitters) it belongs to.
struct FilledPoint {
  Vec3d pos;
  int emitter;
};

// Per instant emitter: points created, and points it contained that an earlier emitter already owned.
struct EmitterFill {
  std::size_t created = 0;
  std::size_t shared = 0;
};

// Fills every instant emitter (jets are skipped) on the lattice; a point belongs to the first emitter
// that contains it. stats has one entry per scene emitter. The caller has checked the budget on
// emitter_index_box(...).count().
std::vector<FilledPoint> fill_instant_emitters(const std::vector<EmitterSpec>& emitters, const Lattice& lattice,
                                               std::vector<EmitterFill>& stats);

// A continuous jet. New particles are born at the start of an inlet of length L behind the outlet and move
// kinematically (age < 0) until they have travelled L; then they become ordinary fluid particles
// (thesis 4.1.6, after Lastiwka et al. 2008). Layers of the section lattice are emitted every d / speed.
class JetEmitter {
 public:
  // Candidates of the section lattice the constructor tests: (2 ceil(r / d) + 1)^2, as a double, so a
  // caller can refuse an absurd section before constructing it.
  static double section_candidates(const EmitterSpec& spec, double spacing);

  // max_particles: most particles one call of advance() may create (the scene's budget); source and
  // index name the jet in messages.
  JetEmitter(const EmitterSpec& spec, double spacing, double inlet_length, float density, double max_particles,
             std::string source, int index);

  // Particles to create during (t, t + dt]. ids are assigned from next_id, which is advanced. Throws
  // SceneError, before allocating, when the step would create more than max_particles.
  std::vector<Spawn> advance(double t, double dt, int32_t& next_id);
  // Particles that fill the inlet at start-up, so the flow is established from the first step.
  std::vector<Spawn> prefill(int32_t& next_id);

  std::size_t section_size() const { return section_.size(); }
  double inlet_length() const { return inlet_length_; }
  const EmitterSpec& spec() const { return spec_; }
  // Layers of the inlet, and where section point s of layer l sits [m] (l = 0 is the farthest from the
  // outlet); prefill() creates exactly these points when the jet starts at t = 0.
  long inlet_layers() const;
  Vec3d inlet_point(long layer, std::size_t s) const;
  // Most particles this jet keeps alive at once during a run of run_time seconds (its lifetime, or the
  // run, plus the inlet).
  double steady_count(double run_time) const;
  // Distance moved since the last layer was born [m]: the emission accumulator a frame stores so a
  // continued run emits its layers at the same steps and places.
  double travelled() const { return travelled_; }
  void set_travelled(double distance) { travelled_ = distance; }

 private:
  void layer(double offset, std::vector<Spawn>& out, int32_t& next_id) const;

  EmitterSpec spec_;
  double spacing_;
  double inlet_length_;
  float density_;
  double max_particles_;
  std::string source_;
  int index_;
  std::vector<Vec3d> section_;  // section lattice points, already in world orientation, relative to centre
  double travelled_ = 0.0;      // distance moved since the last layer was born
};

}  // namespace sph
