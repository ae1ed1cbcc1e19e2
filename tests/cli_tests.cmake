# sph_run command-line tests: bad input must fail with a clear message and the documented exit status
# (1 bad input, 3 unstable simulation); a short good run must print its summary and write metrics.csv.
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
sph_cli_test(too_many_particles
  --exit 1 --max-seconds 10 --stderr "limits.max_particles"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --set resolution.particles_across=5000
     --out ${SPH_CLI_OUT}/too_many_particles)

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
sph_cli_test(steps_zero
  --exit 1 --stderr "--steps must be positive"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --steps 0 --out ${SPH_CLI_OUT}/steps_zero)
sph_cli_test(time_negative
  --exit 1 --stderr "--time must be positive"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --time -1 --out ${SPH_CLI_OUT}/time_negative)
sph_cli_test(unknown_option
  --exit nonzero --stderr "--bogus"
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/thesis_perf_cube.json --bogus)
sph_cli_test(no_scene_argument
  --exit nonzero --stderr "scene"
  -- ${SPH_RUN} --steps 3)

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
  -- ${SPH_RUN} ${SPH_CLI_SCENES}/dam_break.json --set sph.negative_pressure=keep --set sph.viscosity=mueller
     --set resolution.particles_across=10 --frames-every 0 --quiet --out ${SPH_CLI_OUT}/energy_gain)

# --- a good run: thesis 5.2 cube, 3 steps ---------------------------------------------------------------
set(_csv ${SPH_CLI_OUT}/perf_cube/metrics.csv)
set(_columns)
foreach(col time dt step kinetic_energy potential_energy energy_budget density_error_mean density_error_max v_max front_x)
  list(APPEND _columns --csv-column ${_csv} ${col})
endforeach()
sph_cli_test(perf_cube_3_steps
  --exit 0 --clean ${SPH_CLI_OUT}/perf_cube
  --stdout-line "particles: 4096" --stdout-line "steps: 3" --stdout-prefix "ms_per_step: "
  ${_columns}
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
