# Command-line behaviour of sph_demo and sph_bench, and the host back end's OpenMP wait policy (issue 10,
# items 8 and 9). Uses sph_cli_test and the variables of cli_tests.cmake, which is included first.

# --- host: a short OpenMP spin unless the user chose ---------------------------------------------------
# libgomp prints the settings it read at start-up with OMP_DISPLAY_ENV=verbose: the program sets a spin
# count of 1,000 (libgomp's default, 300,000, made host up to 25 times slower on a shared machine). Every
# executable that can create the host back end must have it.
if(SPH_HAVE_HOST)
  foreach(exe sph_run sph_bench sph_demo)
    if(TARGET ${exe})
      add_test(NAME cli_host_short_spin_${exe}
               COMMAND env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose
                       bash ${SPH_CLI_CHECK} --exit 0 --stderr "GOMP_SPINCOUNT = '1000'"
                       -- $<TARGET_FILE:${exe}> --help
               WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
      set_tests_properties(cli_host_short_spin_${exe} PROPERTIES TIMEOUT 60 LABELS cli)
    endif()
  endforeach()
  # The user's own choice is kept.
  add_test(NAME cli_host_user_wait_policy_kept
           COMMAND env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose
                   bash ${SPH_CLI_CHECK} --exit 0 --stderr "OMP_WAIT_POLICY = 'ACTIVE'" -- ${SPH_RUN} --help
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  add_test(NAME cli_host_user_spincount_kept
           COMMAND env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=5000 OMP_DISPLAY_ENV=verbose
                   bash ${SPH_CLI_CHECK} --exit 0 --stderr "GOMP_SPINCOUNT = '5000'" -- ${SPH_RUN} --help
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(cli_host_user_wait_policy_kept cli_host_user_spincount_kept PROPERTIES TIMEOUT 60 LABELS cli)
endif()

# --- sph_bench: every argument checked before the first workload ---------------------------------------
set(SPH_BENCH $<TARGET_FILE:sph_bench>)
sph_cli_test(bench_help --exit 0 --stdout "--workload" -- ${SPH_BENCH} --help)
sph_cli_test(bench_unknown_option --exit 1 --stderr "--bogus" -- ${SPH_BENCH} --bogus)
sph_cli_test(bench_out_not_writable
  --exit 1 --max-seconds 10 --stderr "--out" --stderr "/dev/null/bench" --stderr "cannot create or write"
  -- ${SPH_BENCH} --out /dev/null/bench)
sph_cli_test(bench_unknown_backend
  --exit 1 --max-seconds 10 --stderr "unknown back end" --stderr "\"foo\"" --stderr "available: cpu"
  -- ${SPH_BENCH} --backends cpu foo --out ${SPH_CLI_OUT}/bench_unknown_backend)
sph_cli_test(bench_unknown_workload
  --exit 1 --max-seconds 10 --stderr "unknown --workload \"nope\"" --stderr "thesis_cube_16" --stderr "dam_break_10"
  -- ${SPH_BENCH} --quick --workload nope --out ${SPH_CLI_OUT}/bench_unknown_workload)
sph_cli_test(bench_bad_scenes_dir
  --exit 1 --max-seconds 10 --stderr "no_such_dir/thesis_perf_cube.json" --stderr "cannot open the scene file"
  -- ${SPH_BENCH} --scenes ${SPH_CLI_DATA}/no_such_dir --out ${SPH_CLI_OUT}/bench_bad_scenes_dir)
set(_csv ${SPH_CLI_OUT}/bench_one/bench.csv)
sph_cli_test(bench_one_workload
  --exit 0 --clean ${SPH_CLI_OUT}/bench_one --stdout "thesis_cube_16" --stdout "(median)" --stdout "mean ms per step"
  --csv-column ${_csv} ms_per_step --csv-column ${_csv} ms_mean --min-lines ${_csv} 2
  -- ${SPH_BENCH} --quick --workload thesis_cube_16 --backends cpu --out ${SPH_CLI_OUT}/bench_one)
unset(_csv)

# --- scenes/viscosity_cubes.json shows what it claims: the three cubes differ at 0.4 s --------------------
add_test(NAME scene_viscosity_cubes_differ
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/viscosity_cubes_check.py $<TARGET_FILE:sph_run>
                 ${SPH_CLI_SCENES}/viscosity_cubes.json ${SPH_CLI_OUT}/viscosity_cubes)
set_tests_properties(scene_viscosity_cubes_differ PROPERTIES TIMEOUT 300)
# The same under PBF, which applies the fluids' laminar viscosity since 2026-12-02 (src/solvers/pbf.h,
# apply_viscosity); before, it ignored it and ran all three cubes as water.
add_test(NAME scene_viscosity_cubes_differ_pbf
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/viscosity_cubes_check.py $<TARGET_FILE:sph_run>
                 ${SPH_CLI_SCENES}/viscosity_cubes.json ${SPH_CLI_OUT}/viscosity_cubes_pbf --set solver=pbf)
set_tests_properties(scene_viscosity_cubes_differ_pbf PROPERTIES TIMEOUT 300)

if(NOT SPH_HAVE_DEMO)
  return()
endif()

# --- sph_demo: bad options are refused before any window opens (exit 1; --help exit 0) -----------------
sph_cli_test(demo_help --exit 0 --stdout "--budget-ms" -- ${SPH_DEMO} --help)
sph_cli_test(demo_unknown_option --exit 1 --stderr "--bogus" -- ${SPH_DEMO} --bogus)
sph_cli_test(demo_not_a_number --exit 1 --stderr "--frames" -- ${SPH_DEMO} --frames many)
sph_cli_test(demo_frames_negative --exit 1 --stderr "--frames must be 0" -- ${SPH_DEMO} --frames -1)
sph_cli_test(demo_substeps_zero --exit 1 --stderr "--substeps must be at least 1, got 0" -- ${SPH_DEMO} --substeps 0)
sph_cli_test(demo_budget_nan --exit 1 --stderr "--budget-ms must be a finite" --stderr "got nan" -- ${SPH_DEMO} --budget-ms nan)
sph_cli_test(demo_budget_overflow --exit 1 --stderr "--budget-ms must be a finite" --stderr "got 1e400"
  -- ${SPH_DEMO} --budget-ms 1e400)
sph_cli_test(demo_budget_zero --exit 1 --stderr "--budget-ms must be a finite" -- ${SPH_DEMO} --budget-ms 0)
sph_cli_test(demo_bad_keys --exit 1 --stderr "--keys" --stderr "allowed keys" -- ${SPH_DEMO} --keys Q)
# A scene the set-up refuses (springs under PBF at a frame-sized step) is refused as sph_run refuses it,
# before any window opens (without a display too: not "no display", exit 2).
sph_cli_test(demo_setup_refused --exit 1 --stderr "time_step.dt" --stderr "springs"
  -- env -u DISPLAY ${SPH_DEMO} --scene ${SPH_CLI_SCENES}/viscoelastic.json --set solver=pbf
     --set time_step.mode=fixed --set time_step.dt=0.004 --frames 1)

# --- sph_demo under Xvfb (skipped, exit 77, without xvfb-run) ------------------------------------------
# xvfb_run.sh: the demo under xvfb-run, with the demo's own exit status (see the script).
set(SPH_XVFB bash ${CMAKE_CURRENT_SOURCE_DIR}/data/xvfb_run.sh)
function(sph_demo_xvfb_test name)
  add_test(NAME cli_${name}
           COMMAND bash -c "command -v xvfb-run >/dev/null || exit 77; exec bash \"$0\" \"$@\"" ${SPH_CLI_CHECK} ${ARGN}
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(cli_${name} PROPERTIES TIMEOUT 120 LABELS cli SKIP_RETURN_CODE 77)
endfunction()
set(_jet ${SPH_CLI_SCENES}/water_jet.json --backend cpu --set emitters.0.lifetime=0)
# A jet without lifetime runs as in sph_run (it was refused: "needs about 16500000000743 particles").
sph_demo_xvfb_test(demo_jet_without_lifetime
  --exit 0 --stdout-line "scene: water_jet" --stdout-line "frames: 5"
  -- ${SPH_XVFB} ${SPH_DEMO} --scene ${_jet} --frames 5)
# Past the run time the demo goes on; at limits.max_particles the jet stops, with a message, not an exit.
sph_demo_xvfb_test(demo_jet_stops_at_particle_limit
  --exit 0 --stdout-line "frames: 20" --stderr "emission stopped" --stderr "limits.max_particles = 3000"
  -- ${SPH_XVFB} ${SPH_DEMO} --scene ${_jet} --set run.time=0.01 --set limits.max_particles=3000 --frames 20)
unset(_jet)
# A blow-up during the run ends the demo with exit 3 and sph_run's message.
sph_demo_xvfb_test(demo_blowup
  --exit 3 --stderr "became unstable" --stderr "smaller time step"
  -- ${SPH_XVFB} ${SPH_DEMO} --scene ${SPH_CLI_SCENES}/dam_break.json --backend cpu
     --set time_step.mode=fixed --set time_step.dt=0.05 --frames 20)
# R keeps the command line's overrides: 8^3 particles, not the scene's 16^3.
sph_demo_xvfb_test(demo_reset_keeps_overrides
  --exit 0 --stdout-line "particles: 512"
  -- ${SPH_XVFB} ${SPH_DEMO} --scene ${SPH_CLI_SCENES}/thesis_perf_cube.json --backend cpu
     --set resolution.particles_across=8 --keys R --frames 3)
# [ and ] skip a scene file that cannot be loaded, with a message, in both directions. Written out in full:
# an unbalanced bracket in a CMake list (a function's ARGN) would swallow the arguments after it.
set(_scenes ${SPH_CLI_DATA}/demo_scenes)
set(_skip bash -c "command -v xvfb-run >/dev/null || exit 77 && exec bash \"$0\" \"$@\"" ${SPH_CLI_CHECK})
add_test(NAME cli_demo_next_scene_skips_broken
         COMMAND ${_skip} --exit 0 --stdout-line "scene: demo_test_drop" --stderr "skipped" --stderr "b_broken.json"
                 --stderr "integrater" -- ${SPH_XVFB} ${SPH_DEMO} --scene ${_scenes}/a_cube.json --backend cpu
                 --keys "]" --frames 3
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
# a_cube -> c_drop (wraps) -> b_broken skipped -> a_cube
add_test(NAME cli_demo_previous_scene_skips_broken
         COMMAND ${_skip} --exit 0 --stdout-line "scene: demo_test_cube" --stderr "skipped" --stderr "b_broken.json"
                 -- ${SPH_XVFB} ${SPH_DEMO} --scene ${_scenes}/a_cube.json --backend cpu --keys "[[" --frames 4
         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli_demo_next_scene_skips_broken cli_demo_previous_scene_skips_broken
                     PROPERTIES TIMEOUT 120 LABELS cli SKIP_RETURN_CODE 77)
unset(_skip)
unset(_scenes)
# Paused, the demo sleeps between input events.
add_test(NAME demo_paused_sleeps
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/demo_paused_test.sh ${SPH_DEMO} ${SPH_CLI_SCENES}/thesis_perf_cube.json)
set_tests_properties(demo_paused_sleeps PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77)

# --- sph_demo --replay (issue 14): an sph_run recording played back ------------------------------------
set(_rec ${SPH_CLI_OUT}/replay_recording)
set(_record "rm -rf ${_rec} && ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -b cpu -t 0.1 --frames-every 0.05 -q --out ${_rec}")
# Two frames of 1/30 s at real-time speed reach t = 0.067 s: the frame of 0.05 s is shown.
sph_demo_xvfb_test(demo_replay_plays
  --exit 0 --setup "${_record}" --stdout-line "recorded_frames: 3" --stdout-line "shown_frame: 1"
  --stdout-line "particles: 2000" --file ${SPH_CLI_OUT}/replay.png
  -- ${SPH_XVFB} ${SPH_DEMO} --replay ${_rec} --scene ${SPH_CLI_SCENES}/hydrostatic_tank.json --frames 2
     --screenshot ${SPH_CLI_OUT}/replay.png)
# Space pauses; N steps on twice, to the last frame, and playback does not move it.
sph_demo_xvfb_test(demo_replay_pause_and_step
  --exit 0 --setup "${_record}" --stdout-line "shown_frame: 2"
  -- ${SPH_XVFB} ${SPH_DEMO} --replay ${_rec} --keys " NN" --frames 6)
# A recording that cannot be played is refused before any window opens (no display needed).
sph_cli_test(demo_replay_no_folder --exit 1 --stderr "--replay" --stderr "no such folder"
  -- ${SPH_DEMO} --replay ${SPH_CLI_OUT}/no_such_recording)
sph_cli_test(demo_replay_empty --exit 1 --stderr "no frame_NNNNN.ply"
  --setup "rm -rf ${SPH_CLI_OUT}/replay_empty && mkdir -p ${SPH_CLI_OUT}/replay_empty"
  -- ${SPH_DEMO} --replay ${SPH_CLI_OUT}/replay_empty)
sph_cli_test(demo_replay_corrupt --exit 1 --stderr "frame_00001.ply"
  --setup "${_record} && head -c 300 ${_rec}/frame_00001.ply > ${SPH_CLI_OUT}/cut.ply && mv ${SPH_CLI_OUT}/cut.ply ${_rec}/frame_00001.ply"
  -- ${SPH_DEMO} --replay ${_rec})
sph_cli_test(demo_replay_mixed_runs --exit 1 --stderr "frame_00003.ply" --stderr "another run"
  --setup "${_record} && ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -b cpu -n 1 -q --set resolution.particles_across=8 --frames-every 1 --out ${SPH_CLI_OUT}/replay_other && cp ${SPH_CLI_OUT}/replay_other/frame_00000.ply ${_rec}/frame_00003.ply"
  -- ${SPH_DEMO} --replay ${_rec})
set_tests_properties(cli_demo_replay_plays cli_demo_replay_pause_and_step cli_demo_replay_no_folder cli_demo_replay_empty
                     cli_demo_replay_corrupt cli_demo_replay_mixed_runs PROPERTIES RESOURCE_LOCK replay_recording)
unset(_record)
unset(_rec)

# --- sph_demo --replay with the recording's surface meshes (OpenVDB builds write them) ----------------
if(SPH_WITH_OPENVDB)
  set(_rec ${SPH_CLI_OUT}/replay_meshes)
  set(_record "rm -rf ${_rec} && ${SPH_RUN} ${SPH_CLI_SCENES}/hydrostatic_tank.json -b cpu -t 0.1 --frames-every 0.05 --surface-every 0.05 -q --out ${_rec}")
  # Paused on frame 1 (t = 0.05 s), M's mesh is the one of that time.
  sph_demo_xvfb_test(demo_replay_meshes
    --exit 0 --setup "${_record}" --stdout "surface_00001.ply" --stdout-prefix "mesh_triangles: "
    -- ${SPH_XVFB} ${SPH_DEMO} --replay ${_rec} --keys " NM" --frames 4)
  sph_cli_test(demo_replay_corrupt_mesh --exit 1 --stderr "surface_00001.ply"
    --setup "${_record} && head -c 400 ${_rec}/surface_00001.ply > ${SPH_CLI_OUT}/cut_mesh.ply && mv ${SPH_CLI_OUT}/cut_mesh.ply ${_rec}/surface_00001.ply"
    -- ${SPH_DEMO} --replay ${_rec})
  set_tests_properties(cli_demo_replay_meshes cli_demo_replay_corrupt_mesh PROPERTIES RESOURCE_LOCK replay_meshes)
  unset(_record)
  unset(_rec)
endif()
sph_cli_test(demo_render_mesh_without_replay --exit 1 --stderr "--render mesh" --stderr "--replay"
  -- ${SPH_DEMO} --render mesh)
sph_cli_test(demo_cull_bad_value --exit 1 --stderr "--cull" --stderr "auto"
  -- ${SPH_DEMO} --cull sometimes)
sph_cli_test(demo_cull_without_replay --exit 1 --stderr "--cull" --stderr "--replay"
  -- ${SPH_DEMO} --cull off)
