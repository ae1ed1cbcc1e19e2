# sph_run command-line tests: bad input must fail with a clear message and the documented exit status
# (1 bad input, 3 unstable simulation, 4 output not written, 128 + N stopped by signal N); a short good run
# must print its summary and write metrics.csv; a stopped run must leave a complete metrics.csv.
# Each test runs tests/data/run_check.sh, which checks the exit status, the words on stdout / stderr and
# the files written; a test that only expected failure (WILL_FAIL) would also pass on a crash.
set(SPH_CLI_CHECK ${CMAKE_CURRENT_SOURCE_DIR}/data/run_check.sh)
set(SPH_CLI_DATA ${CMAKE_CURRENT_SOURCE_DIR}/data)
set(SPH_CLI_SCENES ${PROJECT_SOURCE_DIR}/scenes)
set(SPH_CLI_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_out)

# sph_cli_test(NAME CHECKS... -- ARGS...): ARGS are passed to sph_run.
function(sph_cli_test name)
  add_test(NAME cli_${name}
           COMMAND bash ${SPH_CLI_CHECK} ${ARGN}
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(cli_${name} PROPERTIES TIMEOUT 120 LABELS cli)
endfunction()

set(SPH_RUN $<TARGET_FILE:sph_run>)

# --- bad scene files -----------------------------------------------------------------------------------
sph_cli_test(missing_scene
  --exit 1 --stderr "error:" --stderr "no_such_scene.json" --stderr "cannot open the scene file"
  -- ${SPH_RUN} ${SPH_CLI_DATA}/no_such_scene.json --out ${SPH_CLI_OUT}/missing_scene)
sph_cli_test(malformed_json
  --exit 1 --stderr "malformed.json" --stderr "not valid JSON"
  -- ${SPH_RUN} ${SPH_CLI_DATA}/malformed.json --out ${SPH_CLI_OUT}/malformed_json)
sph_cli_test(unknown_key
  --exit 1 --stderr "unknown_key.json" --stderr "integrater" --stderr "unknown key" --stderr "integrator"
  -- ${SPH_RUN} ${SPH_CLI_DATA}/unknown_key.json --out ${SPH_CLI_OUT}/unknown_key)
sph_cli_test(unknown_name
  --exit 1 --stderr "integrator" --stderr "rk4" --stderr "leapfrog" --stderr "modified_velocity_verlet"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set integrator=rk4 --out ${SPH_CLI_OUT}/unknown_name)
sph_cli_test(bad_set
  --exit 1 --stderr "--set" --stderr "key=value"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set integrator --out ${SPH_CLI_OUT}/bad_set)
sph_cli_test(bad_set_path
  --exit 1 --stderr "fluids.7.viscosity" --stderr "not an index"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set fluids.7.viscosity=1 --out ${SPH_CLI_OUT}/bad_set_path)
# A misspelt required key is named as the typo it is, not only as the key that is missing.
sph_cli_test(misspelt_required_key
  --exit 1 --stderr "misspelt_required.json: resolution: is required" --stderr "unknown key \"resolutoin\""
  -- ${SPH_RUN} ${SPH_CLI_DATA}/misspelt_required.json --out ${SPH_CLI_OUT}/misspelt_required_key)
# A key misspelt in --set is blamed on the --set, not on the scene file, and says what is allowed; also
# where the typo is in the first part of the path (the --set created that object).
sph_cli_test(set_unknown_section
  --exit 1 --stderr "error: --set \"resolutoin.particles_across=30\": resolutoin: unknown key" --stderr "resolution"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set resolutoin.particles_across=30 --out ${SPH_CLI_OUT}/set_unknown_section)
sph_cli_test(set_unknown_key
  --exit 1 --stderr "error: --set \"sph.viscosty=0.1\": sph.viscosty: unknown key" --stderr "viscosity"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set sph.viscosty=0.1 --out ${SPH_CLI_OUT}/set_unknown_key)
sph_cli_test(set_out_of_range
  --exit 1 --stderr "error: --set \"fluids.0.viscosity=-1\"" --stderr "out of range"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set fluids.0.viscosity=-1 --out ${SPH_CLI_OUT}/set_out_of_range)
# Command-line errors read like every other error.
sph_cli_test(unexpected_argument
  --exit 1 --stderr "error: The following argument was not expected: extra" --stderr "--help"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json extra --out ${SPH_CLI_OUT}/unexpected_argument)
sph_cli_test(misspelt_option
  --exit 1 --stderr "error: The following arguments were not expected" --stderr "--frams-every: did you mean --frames-every?"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --frams-every 0.1 --out ${SPH_CLI_OUT}/misspelt_option)
# Paths that are not scene files are refused at once, never read forever (/dev/zero) or waited on (FIFO).
sph_cli_test(scene_dev_zero
  --exit 1 --max-seconds 5 --stderr "/dev/zero" --stderr "not a regular file"
  -- ${SPH_RUN} /dev/zero --out ${SPH_CLI_OUT}/scene_dev_zero)
sph_cli_test(scene_directory
  --exit 1 --max-seconds 5 --stderr "is a directory"
  -- ${SPH_RUN} ${SPH_CLI_SCENES} --out ${SPH_CLI_OUT}/scene_directory)
sph_cli_test(scene_fifo
  --exit 1 --max-seconds 5 --clean ${SPH_CLI_OUT}/scene_fifo
  --setup "mkdir -p ${SPH_CLI_OUT}/scene_fifo && mkfifo ${SPH_CLI_OUT}/scene_fifo/scene.json"
  --stderr "scene.json" --stderr "not a regular file"
  -- ${SPH_RUN} ${SPH_CLI_OUT}/scene_fifo/scene.json --out ${SPH_CLI_OUT}/scene_fifo/out)
sph_cli_test(scene_too_large
  --exit 1 --max-seconds 5 --clean ${SPH_CLI_OUT}/scene_too_large
  --setup "mkdir -p ${SPH_CLI_OUT}/scene_too_large && truncate -s 17M ${SPH_CLI_OUT}/scene_too_large/big.json"
  --stderr "big.json" --stderr "17825792 bytes" --stderr "at most 16 MiB"
  -- ${SPH_RUN} ${SPH_CLI_OUT}/scene_too_large/big.json --out ${SPH_CLI_OUT}/scene_too_large/out)
# A value that reads as a number but is not a finite double is named as such, not taken as a string.
sph_cli_test(set_overflowing_number
  --exit 1 --stderr "fluids.0.viscosity=1e400" --stderr "not a finite number"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --set fluids.0.viscosity=1e400 --out ${SPH_CLI_OUT}/set_1e400)
sph_cli_test(set_nan
  --exit 1 --stderr "fluids.0.viscosity=nan" --stderr "not a finite number"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --set fluids.0.viscosity=nan --out ${SPH_CLI_OUT}/set_nan)
# A 0.1 mm cube at 10 um spacing: the kernel sum overflows single precision, so the density right after
# set-up is infinite. The run is refused before its first step, naming the spacing.
sph_cli_test(initial_state_not_finite
  --exit 1 --stderr "thesis_perf_cube.json" --stderr "spacing"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --set "emitters.0.max=[1e-4,1e-4,1e-4]"
     --set resolution.particles_across=10 --steps 3 --out ${SPH_CLI_OUT}/initial_state_not_finite)
sph_cli_test(too_many_particles
  --exit 1 --max-seconds 10 --stderr "limits.max_particles"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --set resolution.particles_across=5000
     --out ${SPH_CLI_OUT}/too_many_particles)
# Memory exhaustion before any check (issue 10): refused at once with the estimate, nothing allocated.
sph_cli_test(jet_section_exhausts_memory
  --exit 1 --max-seconds 5 --stderr "water_jet.json" --stderr "emitters.0 (jet)" --stderr "needs about 10000000000 particles"
  --stderr "limits.max_particles"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/water_jet.json --set resolution.particles_across=100000
     --out ${SPH_CLI_OUT}/jet_section_exhausts_memory)
sph_cli_test(jet_step_exhausts_memory
  --exit 1 --max-seconds 5 --stderr "emitters.0 (jet): one time step" --stderr "needs about"
  --stderr "time_step.dt"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/water_jet.json --set emitters.0.speed=1e4 --set time_step.dt=10
     --out ${SPH_CLI_OUT}/jet_step_exhausts_memory)
# Under an address-space limit (ulimit -v, 600 MB) two million particles (about 1 GB) are refused at
# set-up with the estimate, instead of a std::bad_alloc in the back end.
add_test(NAME cli_memory_limit
         COMMAND bash -c "ulimit -v 600000 && exec bash \"$0\" \"$@\""
                 ${SPH_CLI_CHECK} --exit 1 --max-seconds 5 --stderr "2000000 particles" --stderr "GB (estimate"
                 --stderr "address-space limit"
                 -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set resolution.particles_across=100
                    --out ${SPH_CLI_OUT}/memory_limit
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli_memory_limit PROPERTIES TIMEOUT 120 LABELS cli)

# --- bad options ---------------------------------------------------------------------------------------
sph_cli_test(unknown_backend
  --exit 1 --stderr "unknown back end" --stderr "\"foo\"" --stderr "available: cpu"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --backend foo --out ${SPH_CLI_OUT}/unknown_backend)
# Without a GPU (or without nvcc at configure time) --backend cuda says why and exits 1; where a GPU is
# present the cuda back end runs, so this test is skipped there (exit 77).
add_test(NAME cli_backend_cuda_without_gpu
         COMMAND bash -c "if nvidia-smi -L >/dev/null 2>&1; then exit 77; fi; exec bash \"$0\" \"$@\""
                 ${SPH_CLI_CHECK} --exit 1 --stderr "\"cuda\"" --stderr "cannot run here"
                 -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --backend cuda --out ${SPH_CLI_OUT}/backend_cuda
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli_backend_cuda_without_gpu PROPERTIES TIMEOUT 120 LABELS cli SKIP_RETURN_CODE 77)
# Numeric options: finite, in range, no silent overflow; the message names the option and the range.
sph_cli_test(steps_zero
  --exit 1 --stderr "--steps: 0 is out of range" --stderr "[1, 1000000000000]"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 0 --out ${SPH_CLI_OUT}/steps_zero)
sph_cli_test(steps_overflow
  --exit 1 --stderr "--steps: 99999999999999999999 is out of range"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 99999999999999999999 --out ${SPH_CLI_OUT}/steps_overflow)
sph_cli_test(steps_fraction
  --exit 1 --stderr "--steps: \"2.5\" is not a whole number"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 2.5 --out ${SPH_CLI_OUT}/steps_fraction)
sph_cli_test(time_negative
  --exit 1 --stderr "--time: -1 is out of range" --stderr "allowed (0, 1e+07"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time -1 --out ${SPH_CLI_OUT}/time_negative)
sph_cli_test(time_nan
  --exit 1 --stderr "--time: \"nan\" is not a finite number"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time nan --out ${SPH_CLI_OUT}/time_nan)
sph_cli_test(time_inf
  --exit 1 --stderr "--time: \"inf\" is not a finite number"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time inf --out ${SPH_CLI_OUT}/time_inf)
sph_cli_test(time_huge
  --exit 1 --max-seconds 10 --stderr "--time: 1e30 is out of range" --stderr "allowed (0, 1e+07"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time 1e30 --out ${SPH_CLI_OUT}/time_huge)
sph_cli_test(frames_every_nan
  --exit 1 --stderr "--frames-every: \"nan\" is not a finite number" --stderr "[0, 1e+07] seconds"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --frames-every nan --out ${SPH_CLI_OUT}/frames_every_nan)
sph_cli_test(metrics_every_negative
  --exit 1 --stderr "--metrics-every: -1 is out of range" --stderr "[0, 1e+07] seconds"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --metrics-every -1 --out ${SPH_CLI_OUT}/metrics_every_negative)
# Parse errors exit 1 as documented (not CLI11's own 104 to 109); --help exits 0 and documents the statuses.
sph_cli_test(unknown_option
  --exit 1 --stderr "--bogus"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --bogus)
sph_cli_test(no_scene_argument
  --exit 1 --stderr "scene"
  -- ${SPH_RUN} --steps 3)
sph_cli_test(time_and_steps
  --exit 1 --stderr "excludes"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time 1 --steps 3)
sph_cli_test(help
  --exit 0 --stdout "4 an output could not be written" --stdout "143 stopped by SIGTERM"
  -- ${SPH_RUN} --help)

# --- output that cannot be written: exit 4, the message names the file and the reason ------------------
# metrics.csv is a link to /dev/full, where every write fails with ENOSPC.
sph_cli_test(metrics_disk_full
  --exit 4 --max-seconds 10 --clean ${SPH_CLI_OUT}/metrics_disk_full
  --setup "mkdir -p ${SPH_CLI_OUT}/metrics_disk_full && ln -s /dev/full ${SPH_CLI_OUT}/metrics_disk_full/metrics.csv"
  --stderr "metrics_disk_full/metrics.csv" --stderr "No space left on device"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 3 --quiet --out ${SPH_CLI_OUT}/metrics_disk_full)
sph_cli_test(out_not_a_directory
  --exit 4 --stderr "cannot create the output directory" --stderr "/dev/null/out"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 3 --quiet --out /dev/null/out)

# --- a run stopped by a signal: after the current step, metrics complete, summary printed, 128 + N ------
# The perf cube asked to run 1000 simulated seconds is stopped after 2 s of wall time.
foreach(sig TERM INT)
  if(sig STREQUAL "TERM")
    set(_status 143)
  else()
    set(_status 130)
  endif()
  sph_cli_test(stopped_by_sig${sig}
    --exit ${_status} --clean ${SPH_CLI_OUT}/stopped_${sig} --signal ${sig} 2
    --stdout "interrupted: SIG${sig} at t = " --stdout-prefix "ms_per_step: " --stdout-prefix "ms_per_step_mean: "
    --stdout-prefix "phase_ms_per_step_mean: " --stdout-prefix "steps: "
    --min-lines ${SPH_CLI_OUT}/stopped_${sig}/metrics.csv 3
    --csv-complete ${SPH_CLI_OUT}/stopped_${sig}/metrics.csv
    -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time 1000 --quiet --out ${SPH_CLI_OUT}/stopped_${sig})
endforeach()
unset(_status)
# Killed outright (no handler can run): the rows written more than a second before the kill are on disk.
# One row per 50 steps of the perf cube for 3 s is less than the stdio buffer holds, so without the
# once-per-second flush the file would still hold only its header.
sph_cli_test(metrics_flushed_before_kill
  --exit 137 --clean ${SPH_CLI_OUT}/killed --signal KILL 3
  --min-lines ${SPH_CLI_OUT}/killed/metrics.csv 3
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time 1000 --metrics-every 0.05 --quiet
     --out ${SPH_CLI_OUT}/killed)

# --- a run that blows up: exit 3, a message naming step and particle with advice, metrics kept ---------
# dam_break with a fixed 50 ms step (about 300 times the sound-speed CFL limit) explodes in a few steps.
sph_cli_test(blowup
  --exit 3 --clean ${SPH_CLI_OUT}/blowup
  --stderr "became unstable" --stderr "step" --stderr "particle id" --stderr "smaller time step"
  --file ${SPH_CLI_OUT}/blowup/metrics.csv
  --min-lines ${SPH_CLI_OUT}/blowup/metrics.csv 2
  --csv-column ${SPH_CLI_OUT}/blowup/metrics.csv v_max
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set time_step.mode=fixed --set time_step.dt=0.05
     --frames-every 0 --quiet --out ${SPH_CLI_OUT}/blowup)

# --- a run that gains energy: exit 3 with the energy message and what to change, metrics kept ----------
# dam_break with the old unsafe defaults (negative pressure kept, water's Mueller viscosity only, penalty
# walls) holds 1.2 times its budget within about 20 steps (tests/test_energy.cpp).
sph_cli_test(energy_gain
  --exit 3 --clean ${SPH_CLI_OUT}/energy_gain
  --stderr "became unstable" --stderr "particle id" --stderr "kinetic energy" --stderr "energy budget"
  --stderr "sph.negative_pressure = \"clamp\""
  --csv-column ${SPH_CLI_OUT}/energy_gain/metrics.csv energy_budget
  --min-lines ${SPH_CLI_OUT}/energy_gain/metrics.csv 10
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set sph.negative_pressure=keep --set sph.viscosity=mueller --set fluids.0.artificial_viscosity=0
     --set resolution.particles_across=10 --frames-every 0 --quiet --out ${SPH_CLI_OUT}/energy_gain)

# --- a drop whose surface tension outruns its damping: exit 3 naming the surface tension, metrics kept ----
# drop_oscillation at 1000 N/m gains more kinetic energy than its lost area can release within 10 steps
# (before the budget counted only that, it flew apart and the run ended with exit 0).
sph_cli_test(surface_tension_energy_gain
  --exit 3 --clean ${SPH_CLI_OUT}/sigma_gain
  --stderr "became unstable" --stderr "kinetic energy" --stderr "surface energy" --stderr "fluids.N.surface_tension"
  --stderr "Ohnesorge" --file ${SPH_CLI_OUT}/sigma_gain/metrics.csv
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/drop_oscillation.json --set fluids.0.surface_tension=1000 --time 0.1
     --frames-every 0 --quiet --out ${SPH_CLI_OUT}/sigma_gain)

# --- a good run: thesis 5.2 cube, 3 steps ---------------------------------------------------------------
set(_csv ${SPH_CLI_OUT}/perf_cube/metrics.csv)
set(_columns)
foreach(col time dt step kinetic_energy potential_energy energy_budget density_error_mean density_error_max v_max front_x)
  list(APPEND _columns --csv-column ${_csv} ${col})
endforeach()
sph_cli_test(perf_cube_3_steps
  --exit 0 --clean ${SPH_CLI_OUT}/perf_cube
  --stdout-line "particles: 4096" --stdout-line "steps: 3" --stdout-prefix "ms_per_step: "
  --stdout-prefix "ms_per_step_mean: " --stdout-prefix "phase_ms_per_step_mean: "
  ${_columns} --csv-complete ${_csv}
  --min-lines ${_csv} 5
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 3 --quiet --out ${SPH_CLI_OUT}/perf_cube)
unset(_csv)
unset(_columns)

# --- sph_demo ------------------------------------------------------------------------------------------
if(SPH_HAVE_DEMO)
  set(SPH_DEMO $<TARGET_FILE:sph_demo>)
  sph_cli_test(demo_bad_scene
    --exit 1 --stderr "error:" --stderr "no_such_scene.json"
    -- ${SPH_DEMO} --scene ${SPH_CLI_DATA}/no_such_scene.json)
  sph_cli_test(demo_screenshot_without_frames
    --exit 1 --stderr "--screenshot needs --frames"
    -- ${SPH_DEMO} --scene ${SPH_CLI_SCENES}/dam_break.json --screenshot x.png)
  # Without a display the demo says so and how to get a picture anyway (exit 2).
  add_test(NAME cli_demo_no_display
           COMMAND env -u DISPLAY bash ${SPH_CLI_CHECK} --exit 2 --stderr "no display" --stderr "xvfb-run"
                   -- ${SPH_DEMO} --scene ${SPH_CLI_SCENES}/dam_break.json --backend cpu
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(cli_demo_no_display PROPERTIES TIMEOUT 120 LABELS cli)
endif()

# --metrics-every thins the rows but the final state always has its row: the last row's step is the
# summary's step count.
add_test(NAME cli_metrics_every_keeps_final_row
         COMMAND bash -c "set -e; out=$1; rm -rf $out; $0 $2 --set resolution.particles_across=6 --time 0.05 --metrics-every 0.02 --quiet --out $out > $out.txt; steps=$(sed -n 's/^steps: //p' $out.txt); last=$(tail -n 1 $out/metrics.csv | cut -d, -f3); echo \"summary steps $steps, last row step $last\"; [ \"$steps\" = \"$last\" ]"
                 ${SPH_RUN} ${SPH_CLI_OUT}/metrics_every_final ${SPH_CLI_SCENES}/dam_break.json
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli_metrics_every_keeps_final_row PROPERTIES TIMEOUT 120 LABELS cli)

# Particles that leave the domain are still simulated (the grid covers any position), and counted: in
# metrics.csv, the summary and a warning. The cube starts inside and falls 7 cm through the bottom.
sph_cli_test(leaves_domain
  --clean ${SPH_CLI_OUT}/leaves_domain --exit 0
  --stdout-line "particles_outside_domain: 1000 (most in a metrics row: 1000)" --stderr "1000 particles left the domain"
  --csv-column ${SPH_CLI_OUT}/leaves_domain/metrics.csv outside_domain
  -- ${SPH_RUN} ${SPH_CLI_DATA}/leaves_domain.json -q --out ${SPH_CLI_OUT}/leaves_domain)
sph_cli_test(stays_in_domain
  --clean ${SPH_CLI_OUT}/stays_in_domain --exit 0 --stdout-line "particles_outside_domain: 0 (most in a metrics row: 0)"
  -- ${SPH_RUN} ${SPH_CLI_DATA}/leaves_domain.json -q --time 0.02 --out ${SPH_CLI_OUT}/stays_in_domain)

# --- the pressure solvers (issue 12): "solver" and its block through --set, on the hydrostatic tank ----
sph_cli_test(solver_zero_iterations
  --exit 1 --stderr "dfsph.max_iterations=0" --stderr "dfsph.max_iterations: value 0 is out of range" --stderr "[1, 10000]"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=dfsph --set dfsph.max_iterations=0
     --out ${SPH_CLI_OUT}/solver_zero_iterations)
sph_cli_test(solver_unknown_name
  --exit 1 --stderr "\"sph\"" --stderr "\"wcsph\", \"dfsph\", \"pbf\""
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=sph --out ${SPH_CLI_OUT}/solver_unknown_name)
sph_cli_test(solver_block_of_another_solver
  --exit 1 --stderr "dfsph: this block holds the settings of solver \"dfsph\", but solver is \"pbf\""
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=pbf --set dfsph.max_iterations=50
     --out ${SPH_CLI_OUT}/solver_block_of_another_solver)
# 50 ms at 5 mm spacing: gravity alone would move a particle at rest by 2.5 spacings in one step.
sph_cli_test(solver_step_too_long
  --exit 1 --stderr "hydrostatic_tank.json: time_step.dt" --stderr "solver \"dfsph\"" --stderr "sqrt(d / |g|) = 0.0225"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=dfsph --set time_step.mode=fixed
     --set time_step.dt=0.05 --out ${SPH_CLI_OUT}/solver_step_too_long)
sph_cli_test(dfsph_tank_20_steps
  --exit 0 --clean ${SPH_CLI_OUT}/dfsph_tank
  --stdout-line "solver: dfsph, sph.kernel: cubic_spline" --stdout-line "steps: 20" --stdout-prefix "density_solver_iterations: mean "
  --stdout-prefix "divergence_solver_iterations: mean " --stdout-prefix "solver_capped_steps: "
  --csv-column ${SPH_CLI_OUT}/dfsph_tank/metrics.csv solver_iterations
  --csv-column ${SPH_CLI_OUT}/dfsph_tank/metrics.csv solver_density_error
  --csv-column ${SPH_CLI_OUT}/dfsph_tank/metrics.csv divergence_iterations
  --csv-column ${SPH_CLI_OUT}/dfsph_tank/metrics.csv divergence_error
  --csv-complete ${SPH_CLI_OUT}/dfsph_tank/metrics.csv
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=dfsph -n 20 -q --out ${SPH_CLI_OUT}/dfsph_tank)
# PBF at its dam-break target step, 4 ms, with the default 4 iterations.
sph_cli_test(pbf_tank_10_steps
  --exit 0 --clean ${SPH_CLI_OUT}/pbf_tank
  --stdout-line "solver: pbf" --stdout-line "steps: 10" --stdout-line "constraint_iterations: mean 4, max 4"
  --csv-column ${SPH_CLI_OUT}/pbf_tank/metrics.csv solver_iterations
  --csv-column ${SPH_CLI_OUT}/pbf_tank/metrics.csv solver_density_error
  --csv-complete ${SPH_CLI_OUT}/pbf_tank/metrics.csv
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=pbf --set time_step.mode=fixed
     --set time_step.dt=0.004 -n 10 -q --out ${SPH_CLI_OUT}/pbf_tank)

# Non-convergence is reported, not hidden: a tolerance no solve reaches in the few iterations allowed.
# run_check.sh checks the words; the summary's count of capped solves must be above zero.
function(sph_cli_capped_test name)
  add_test(NAME cli_${name}
           COMMAND bash -c "out=$(bash \"$0\" \"$@\"); status=$?; echo \"$out\"; [ $status -eq 0 ] || exit 1; echo \"$out\" | grep -Eq '^solver_capped_steps: [1-9][0-9]*$' || { echo 'FAILED: solver_capped_steps is not above 0'; exit 1; }"
                   ${SPH_CLI_CHECK} ${ARGN}
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(cli_${name} PROPERTIES TIMEOUT 120 LABELS cli)
endfunction()
# DFSPH with one iteration against a tolerance of 1e-7: the first steps from the lattice at rest density
# converge, the rest do not; the run goes on (exit 0) and says so.
sph_cli_capped_test(dfsph_not_converged
  --exit 0 --clean ${SPH_CLI_OUT}/dfsph_capped
  --stderr "warning: the density solver did not converge in " --stderr " of 30 steps" --stderr "dfsph.max_iterations = 1"
  --stdout-line "density_solver_iterations: mean 1, max 1"
  --csv-column ${SPH_CLI_OUT}/dfsph_capped/metrics.csv solver_density_error
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=dfsph --set dfsph.max_iterations=1
     --set dfsph.min_iterations=1 --set dfsph.density_tolerance=1e-7 -n 30 -q --out ${SPH_CLI_OUT}/dfsph_capped)
# PBF with two iterations against 1e-7: every step is capped, the column holds for 30 steps (exit 0).
sph_cli_capped_test(pbf_not_converged
  --exit 0 --clean ${SPH_CLI_OUT}/pbf_capped
  --stderr "warning: the constraint solve did not converge in 30 of 30 steps" --stderr "pbf.iterations = 2"
  --stdout-line "constraint_iterations: mean 2, max 2" --stdout-line "solver_capped_steps: 30"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=pbf --set pbf.iterations=2
     --set pbf.density_tolerance=1e-7 -n 30 -q --out ${SPH_CLI_OUT}/pbf_capped)
# With one iteration at 4 ms the compression left by each step piles up (about 2% a step) until the run
# stops with the blow-up message (exit 3); the capped solves are still reported.
sph_cli_capped_test(pbf_one_iteration_blows_up
  --exit 3 --clean ${SPH_CLI_OUT}/pbf_one_iteration
  --stderr "became unstable" --stderr "mean compression" --stderr "Raise pbf.iterations"
  --stderr "warning: the constraint solve did not converge in " --stderr "pbf.iterations = 1"
  --min-lines ${SPH_CLI_OUT}/pbf_one_iteration/metrics.csv 2
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --set solver=pbf --set pbf.iterations=1
     --set pbf.density_tolerance=1e-7 --set time_step.mode=fixed --set time_step.dt=0.004 -n 30 -q
     --out ${SPH_CLI_OUT}/pbf_one_iteration)

# --- meshes (issue 13): walls of boundary particles only; a missing file or a non-OBJ is named -----------
sph_cli_test(mesh_needs_boundary_particles
  --exit 1 --stderr "meshes" --stderr "sph.walls=particles"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/mesh_obstacle.json --set sph.walls=mirror --steps 1 --out ${SPH_CLI_OUT}/mesh_walls)
sph_cli_test(mesh_missing_file
  --exit 1 --stderr "meshes.0" --stderr "no_such_cup.obj"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/mesh_obstacle.json --set meshes.0.file=no_such_cup.obj --steps 1 --out ${SPH_CLI_OUT}/mesh_missing)
sph_cli_test(mesh_not_obj
  --exit 1 --stderr "meshes.0.file" --stderr "OBJ"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/mesh_obstacle.json --set meshes.0.file=cup.ply --steps 1 --out ${SPH_CLI_OUT}/mesh_ply)
sph_cli_test(mesh_obstacle_runs
  --exit 0 --stdout "meshes.0:" --stdout "boundary particles" --file ${SPH_CLI_OUT}/mesh_runs/metrics.csv
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/mesh_obstacle.json --steps 5 --out ${SPH_CLI_OUT}/mesh_runs)

# --- rigid bodies (issue 13): WCSPH only; a prescribed body needs its oscillation, inside the walls -------
sph_cli_test(bodies_not_pbf
  --exit 1 --stderr "bodies" --stderr "wcsph" --stderr "dfsph" --stderr "pbf"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json --set solver=pbf --steps 1 --out ${SPH_CLI_OUT}/bodies_pbf)
sph_cli_test(bodies_dfsph_runs
  --exit 0 --stdout "body: bodies.0 (box)" --stdout "solver: dfsph"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json --set solver=dfsph --steps 10 --out ${SPH_CLI_OUT}/bodies_dfsph)
sph_cli_test(bodies_prescribed_without_oscillation
  --exit 1 --stderr "bodies.0.oscillation" --stderr "prescribed"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json --set bodies.0.motion=prescribed --steps 1 --out ${SPH_CLI_OUT}/bodies_osc)
sph_cli_test(bodies_stroke_through_wall
  --exit 1 --stderr "bodies.0" --stderr "through a wall"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/wave_maker.json --set "bodies.0.oscillation.amplitude=[0.5,0,0]" --steps 1 --out ${SPH_CLI_OUT}/bodies_stroke)

# --- water-height probes (scene key "probes"): columns depth_<name>; a bad name or no gravity is refused ---
sph_cli_test(probes_columns
  --exit 0 --csv-column ${SPH_CLI_OUT}/probes/metrics.csv depth_H1 --csv-column ${SPH_CLI_OUT}/probes/metrics.csv depth_box_front
  --csv-column ${SPH_CLI_OUT}/probes/metrics.csv deepest_in_solid --csv-complete ${SPH_CLI_OUT}/probes/metrics.csv
  --stdout "deepest_in_solid:"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break_obstacle.json --set resolution.spacing=0.05 --steps 5 --out ${SPH_CLI_OUT}/probes)
sph_cli_test(probes_bad_name
  --exit 1 --stderr "probes.0.name" --stderr "letters, digits and '_'"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break_obstacle.json --set "probes.0.name=H-1" --steps 1 --out ${SPH_CLI_OUT}/probes_name)
sph_cli_test(probes_same_name
  --exit 1 --stderr "probes.1.name" --stderr "names two probes"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break_obstacle.json --set "probes.1.name=H1" --steps 1 --out ${SPH_CLI_OUT}/probes_twice)
sph_cli_test(probes_without_gravity
  --exit 1 --stderr "probes" --stderr "gravity"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break_obstacle.json --set "gravity=[0,0,0]" --steps 1 --out ${SPH_CLI_OUT}/probes_g)
sph_cli_test(probes_position_not_finite
  --exit 1 --stderr "probes.2.position"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break_obstacle.json --set "probes.2.position=[1,\"x\",0]" --steps 1 --out ${SPH_CLI_OUT}/probes_pos)
sph_cli_test(bodies_flap_through_wall
  --exit 1 --stderr "bodies.0" --stderr "through a wall" --stderr "angle"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/wave_maker.json
     "--set=bodies.0.oscillation={\"angle\": 60, \"axis\": [0, 0, 1], \"pivot\": [0.05, 0, 0.05], \"period\": 0.8}"
     --steps 1 --out ${SPH_CLI_OUT}/bodies_flap)
sph_cli_test(bodies_flap_without_pivot
  --exit 1 --stderr "bodies.0.oscillation.pivot" --stderr "axis"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/wave_maker.json
     "--set=bodies.0.oscillation={\"angle\": 5, \"axis\": [0, 0, 1], \"period\": 0.8}" --steps 1 --out ${SPH_CLI_OUT}/bodies_pivot)

# --- no leaks (issue 13): every shipped scene with walls, as shipped (or coarser where named), checked after
# every step: no fluid particle ever gets more than one spacing deep into a wall, obstacle, mesh or body
# (sph_run warns "deep into a solid" then; solid_penetration.h). Times cover the first impacts.
function(sph_leak_test scene)
  sph_cli_test(leak_${scene}
    --exit 0 --stdout "deepest_in_solid:" --no-stderr "deep into a solid" --no-stderr "left the domain"
    -- ${SPH_RUN} ${SPH_CLI_SCENES}/${scene}.json --backend host --metrics-every 0 --frames-every 0 --quiet ${ARGN}
       --out ${SPH_CLI_OUT}/leak_${scene})
  set_tests_properties(cli_leak_${scene} PROPERTIES TIMEOUT 300 LABELS "cli;leak")
endfunction()
sph_leak_test(dam_break)                                  # penalty walls, 0.3 s
sph_leak_test(obstacles)                                  # a sphere and a quadric, 0.6 s
sph_leak_test(mesh_obstacle --time 0.6)                   # the cup, hit at about 0.25 s
sph_leak_test(floating_box --time 0.6)                    # the box lands on the water
sph_leak_test(wave_maker --set resolution.spacing=0.02 --time 2)
sph_leak_test(dam_break_obstacle --set resolution.spacing=0.05 --time 2)
sph_leak_test(water_jet --set resolution.particles_across=7 --time 1.2)
sph_leak_test(viscosity_cubes --time 0.6)                # landing at 0.15 s, the thin cube up the walls by 0.3 s
sph_leak_test(hydrostatic_tank)

# --- mesh bodies (issue 13): a closed OBJ as a rigid body; a missing or open one is refused by name ------------
sph_cli_test(mesh_body_floats
  --exit 0 --stdout "bodies.0 (mesh):" --stdout "body: bodies.0 (mesh)"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json
     "--set=bodies.0={\"type\": \"mesh\", \"file\": \"meshes/cup.obj\", \"scale\": 0.1, \"translate\": [0.2, 0.17, 0.1], \"density\": 300}"
     --set resolution.spacing=0.0125 --steps 20 --out ${SPH_CLI_OUT}/mesh_body)
sph_cli_test(mesh_body_open
  --exit 1 --stderr "bodies.0 (mesh)" --stderr "open_box.obj" --stderr "open"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json
     "--set=bodies.0={\"type\": \"mesh\", \"file\": \"${SPH_CLI_DATA}/open_box.obj\", \"scale\": 0.05, \"translate\": [0.2, 0.17, 0.1], \"density\": 300}"
     --steps 1 --out ${SPH_CLI_OUT}/mesh_body_open)
sph_cli_test(mesh_body_missing
  --exit 1 --stderr "bodies.0 (mesh)" --stderr "nope.obj"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json "--set=bodies.0={\"type\": \"mesh\", \"file\": \"nope.obj\", \"density\": 300}"
     --steps 1 --out ${SPH_CLI_OUT}/mesh_body_missing)
sph_cli_test(bodies_too_light
  --exit 1 --stderr "bodies.0 (box)" --stderr "below 1% of the fluid's" --stderr "at least 10 kg/m^3"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json
     "--set=bodies=[{\"type\": \"box\", \"min\": [0.16, 0.16, 0.06], \"max\": [0.24, 0.22, 0.14], \"mass\": 1e-9}]"
     --steps 1 --out ${SPH_CLI_OUT}/bodies_light)
sph_cli_test(bodies_columns
  --exit 0 --csv-column ${SPH_CLI_OUT}/bodies_columns/metrics.csv body0_y --csv-column ${SPH_CLI_OUT}/bodies_columns/metrics.csv body0_qw
  --csv-column ${SPH_CLI_OUT}/bodies_columns/metrics.csv body0_fy --csv-complete ${SPH_CLI_OUT}/bodies_columns/metrics.csv
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/floating_box.json --set resolution.spacing=0.0125 --steps 5 --out ${SPH_CLI_OUT}/bodies_columns)
sph_cli_test(probes_outside_domain
  --exit 0 --stderr "probes.0 (\"H1\")" --stderr "outside the domain" --stderr "will read 0"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break_obstacle.json --set resolution.spacing=0.05 "--set=probes.0.position=[5,0,0.5]"
     --steps 2 --out ${SPH_CLI_OUT}/probes_outside)

# --- surface meshes (issue 14; OpenVDB builds) ----------------------------------------------------------
if(SPH_WITH_OPENVDB)
  set(SPH_SURFACE $<TARGET_FILE:sph_surface>)
  # A short run writes a surface mesh at the start and at each interval, beside its frames.
  sph_cli_test(surface_every
    --exit 0 --clean ${SPH_CLI_OUT}/surface_every --file ${SPH_CLI_OUT}/surface_every/surface_00000.ply
    --file ${SPH_CLI_OUT}/surface_every/surface_00002.ply
    -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -t 0.02 --frames-every 0.01 --surface-every 0.01 -q
       --out ${SPH_CLI_OUT}/surface_every)
  sph_cli_test(surface_every_nan
    --exit 1 --stderr "--surface-every" --stderr "not a finite number"
    -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --surface-every nan --out ${SPH_CLI_OUT}/surface_every_nan)
  sph_cli_test(surface_resolution_range
    --exit 1 --stderr "--surface-resolution" --stderr "[1, 8]"
    -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --surface-every 0.1 --surface-resolution 50
       --out ${SPH_CLI_OUT}/surface_resolution_range)
  # sph_surface meshes the frames of a folder (the frames of surface_every), next to them or into --out.
  sph_cli_test(surface_tool
    --exit 0 --clean ${SPH_CLI_OUT}/surface_tool --stdout "[3/3]" --stdout "triangles"
    --file ${SPH_CLI_OUT}/surface_tool/surface_00001.ply
    --setup "${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -t 0.02 --frames-every 0.01 -q --out ${SPH_CLI_OUT}/surface_tool"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/surface_tool)
  sph_cli_test(surface_tool_missing
    --exit 1 --stderr "no_such_folder" --stderr "no such file or folder"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/no_such_folder)
  sph_cli_test(surface_tool_empty_folder
    --exit 1 --clean ${SPH_CLI_OUT}/surface_tool_empty --stderr "no frame_NNNNN.ply"
    --setup "mkdir -p ${SPH_CLI_OUT}/surface_tool_empty"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/surface_tool_empty)
  sph_cli_test(surface_tool_corrupt_frame
    --exit 1 --clean ${SPH_CLI_OUT}/surface_tool_corrupt --stderr "frame_00000.ply"
    --setup "mkdir -p ${SPH_CLI_OUT}/surface_tool_corrupt && printf 'ply\\nformat ascii 1.0\\nend_header\\n' > ${SPH_CLI_OUT}/surface_tool_corrupt/frame_00000.ply"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/surface_tool_corrupt)
  # A mesh that exists (here the run's own, numbered by time) is refused without --force, and kept.
  sph_cli_test(surface_tool_exists
    --exit 1 --clean ${SPH_CLI_OUT}/surface_tool_exists --stderr "surface_00000.ply exists" --stderr "--force"
    --setup "${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -n 1 --frames-every 1 --surface-every 1 -q --out ${SPH_CLI_OUT}/surface_tool_exists"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/surface_tool_exists)
  sph_cli_test(surface_tool_force
    --exit 0 --clean ${SPH_CLI_OUT}/surface_tool_force --stdout "[1/1]"
    --setup "${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -n 1 --frames-every 1 --surface-every 1 -q --out ${SPH_CLI_OUT}/surface_tool_force"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/surface_tool_force --force)
  # An output folder that cannot be made: exit 4, naming it.
  sph_cli_test(surface_tool_unwritable
    --exit 4 --stderr "cannot create the output folder" --stderr "/dev/null/meshes"
    --setup "${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -n 1 --frames-every 1 -q --out ${SPH_CLI_OUT}/surface_tool_unwritable"
    -- ${SPH_SURFACE} ${SPH_CLI_OUT}/surface_tool_unwritable --out /dev/null/meshes)
  sph_cli_test(surface_resolution_alone
    --exit 1 --stderr "--surface-resolution" --stderr "--surface-every"
    -- ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json --surface-resolution 3 --out ${SPH_CLI_OUT}/surface_resolution_alone)
  sph_cli_test(surface_tool_resolution
    --exit 1 --stderr "--resolution" --stderr "[1, 8]"
    -- ${SPH_SURFACE} ${SPH_CLI_DATA} --resolution 0)
endif()

# --- several fluids, surface tension, springs (issue 15): limits refused by key, exit 1 -----------------
sph_cli_test(multiphase_mass_density_refused
  --exit 1 --stderr "sph.multiphase" --stderr "1.25" --stderr "number_density"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/two_layers.json --set sph.multiphase=mass_density --out ${SPH_CLI_OUT}/multiphase_mass)
sph_cli_test(multiphase_soft_light_fluid
  --exit 1 --stderr "fluids.1.speed_of_sound" --stderr "at least 150"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/two_layers.json --set fluids.1.rest_density=1 --out ${SPH_CLI_OUT}/multiphase_soft)
sph_cli_test(surface_tension_too_soft
  --exit 1 --stderr "fluids.0.speed_of_sound" --stderr "surface_tension" --stderr "at least"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/drop_oscillation.json --set fluids.0.speed_of_sound=5 --set solver=wcsph --set sph.surface_tension=cohesion --out ${SPH_CLI_OUT}/sigma_soft)
sph_cli_test(springs_pbf_frame_step_refused
  --exit 1 --stderr "time_step.dt" --stderr "springs" --stderr "pbf"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/viscoelastic.json --set solver=pbf --set time_step.mode=fixed --set time_step.dt=0.004
     --out ${SPH_CLI_OUT}/springs_pbf)
sph_cli_test(springs_dfsph_fixed_step_refused
  --exit 1 --stderr "time_step.dt" --stderr "springs" --stderr "adaptive"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/viscoelastic.json --set solver=dfsph --set time_step.mode=fixed --set time_step.dt=0.001
     --out ${SPH_CLI_OUT}/springs_dfsph_fixed)
sph_cli_test(interface_tension_csf_contact_refused
  --exit 1 --stderr "interface_tension" --stderr "fluids.0.contact_angle"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/compound_drop.json --set fluids.0.contact_angle=90 --out ${SPH_CLI_OUT}/interface_contact)
sph_cli_test(contact_angle_csf_refused
  --exit 1 --stderr "fluids.0.contact_angle" --stderr "cohesion"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/wetting.json --set sph.surface_tension=csf --out ${SPH_CLI_OUT}/contact_csf)
sph_cli_test(contact_angle_out_of_range
  --exit 1 --stderr "fluids.1.contact_angle" --stderr "out of range" --stderr "180"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/wetting.json --set fluids.1.contact_angle=0 --out ${SPH_CLI_OUT}/contact_zero)
sph_cli_test(interface_tension_unknown_fluid
  --exit 1 --stderr "interface_tension.0.fluids.1" --stderr "no fluid named" --stderr "the fluids: \"outer\", \"inner\""
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/interface_drop.json --set interface_tension.0.fluids.1=oil --out ${SPH_CLI_OUT}/interface_oil)
sph_cli_test(viscoelastic_short_run
  --exit 0 --stdout "up to 26 per particle" --file ${SPH_CLI_OUT}/viscoelastic_run/metrics.csv
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/viscoelastic.json --time 0.02 --quiet --out ${SPH_CLI_OUT}/viscoelastic_run)

# --- sph_oscillators: bad options and an output it cannot write, exit 1 with the option named --------------
set(SPH_OSCILLATORS $<TARGET_FILE:sph_oscillators>)
sph_cli_test(oscillators_unknown_option
  --exit 1 --stderr "error:" --stderr "--bogus"
  -- ${SPH_OSCILLATORS} --bogus)
sph_cli_test(oscillators_unwritable_out
  --exit 1 --stderr "--out" --stderr "/dev/null/x" --stderr "cannot write"
  -- ${SPH_OSCILLATORS} --out /dev/null/x)
