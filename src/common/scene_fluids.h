// What a scene's fluids ask of the multi-fluid formulation and of the solver (issue 15), checked when the
// scene is loaded (scene_loader.cpp): a combination that cannot hold the fluids at rest is refused with the
// key and the limit, rather than run into a blow-up.
#pragma once

#include "scene.h"

namespace sph {

// Density ratios between the scene's fluids (SceneError naming the key otherwise):
// - sph.multiphase "mass_density": rest densities within a factor kMassDensityRatioLimit of each other (a
//   water-over-oil layering at ratio 2 rose 6 cm in 0.1 s; at 1.25 it stayed near rest);
// - "number_density": Tait's B = rho0 c0^2 / 7 of any two fluids within a factor kTaitRatioLimit (the
//   pressure must be about the same function of the number density on both sides of an interface: layers
//   at density ratio 100 with one c0, B ratio 0.01, moved at 2.6 m/s; ratio 10 and ratio 1000 with the light
//   fluid's c0 raised to B ratio 0.1 stayed below 0.1 m/s; docs/results.md);
// - the Tait limit applies to WCSPH only (DFSPH and PBF have no equation of state).
void check_fluid_ratios(const Scene& scene);

// Surface tension against the equation of state (WCSPH): the cohesion's internal pressure
// (cohesion_pressure, calibration.h) may compress a fluid by at most kCohesionCompressionLimit, i.e.
// 8.23 sigma / h <= limit rho0 c0^2 (SceneError naming fluids.N.speed_of_sound and its least value
// otherwise). Under a softer fluid the cohesion crushes the drop it should shape: a 0.1 m cube with
// sigma = 4 N/m and c0 = 5 m/s (compression 10%) flew apart. The same for each interface tension's cohesion
// between two fluids (SceneError naming interface_tension.N.sigma; unchecked, 100 N/m between two fluids
// of c0 = 20 m/s blew up at 7 ms).
void check_surface_tension(const Scene& scene, double h);

// Springs (springs.h) only where they can be kept: on fluids created at the start (not by jets, not from an
// initial_state frame, which holds no springs), and under WCSPH with an elastic wave speed sqrt(G / rho0) at
// most kElasticWaveLimit c0, so that the sound speed's time step also resolves the springs (DFSPH's and PBF's
// steps have a limit of the springs' own, time_step.h). SceneError naming the key otherwise.
void check_springs(const Scene& scene);

// A contact angle only where it holds: a fluid with surface_tension > 0 and a solver with a wall condition
// for it (not PBF, which has neither the adhesion nor the continuum surface force's wall images); under the cohesion model (Akinci's adhesion, cohesion_energy.h) walls of boundary particles or rigid
// bodies for it to act on; under the continuum surface force (its wall condition, surface_tension_csf.h) a
// wall it can act at and an angle in [kCsfContactAngleMin, kCsfContactAngleMax], the range it was measured to
// hold. SceneError naming the key otherwise.
void check_contact_angle(const Scene& scene);

// An interface tension (scene key interface_tension) only with a solver with surface tension (not PBF), and
// under the continuum surface force (surface_tension_csf.h, csf_interface_share) only between the scene's two
// fluids, none of which has a contact angle (the share reads no images). SceneError naming
// the key otherwise.
void check_interface_tension(const Scene& scene);

// Under the continuum surface force an interface tension holds where at most one of its two fluids meets the
// gas (a drop of one inside the other; both in a container they fill), not along a line where both meet it:
// there each particle's share (surface_tension_csf.h) takes the interface's tension along its own fluid's
// rounded outline, and two drops side by side flew apart (docs/results.md). Checked on the start's particles
// (s.particles, the set-up's constants): a particle meets the gas where more than kGasDeficit of its colour is
// missing (1 - c_own - c_other, with the share's kernel: params.h, density_cubic_spline; 0 inside the start's lattice and at an interface, about 0.2 on a face
// of a block and more at its edges) and no container wall or plane is within h (walls read as missing
// colour). SceneError naming interface_tension.N otherwise. A drop that reaches the free surface later (a rising
// drop) is not caught.
struct Setup;
void check_interface_gas(const Scene& scene, const Setup& s);
constexpr double kGasDeficit = 0.1;

constexpr double kElasticWaveLimit = 0.5;
constexpr double kCohesionCompressionLimit = 0.03;
constexpr double kMassDensityRatioLimit = 1.25;
constexpr double kTaitRatioLimit = 10.0;

}  // namespace sph
