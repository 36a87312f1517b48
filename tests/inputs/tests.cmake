# Inputs a user gives the command line (tests/inputs/README.md): the case schema against every case and
# against planted wrong ones; the exit status of a checkpoint that cannot be restarted from.
add_test(NAME "inputs: dem2d schema validates every case and refuses planted wrong ones as the reader does"
         COMMAND ${DEM2D_SYSTEM_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/inputs/check_schema.py
                 $<TARGET_FILE:dem2d> ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/inputs_schema)
# A checkpoint is an input: a damaged one (a crafted file without its checksum) and a file that is no
# checkpoint are exit status 2, as --help says, not 4 (an output that cannot be written).
add_test(NAME "inputs: a damaged checkpoint is exit status 2"
         COMMAND ${DEM2D_EXPECT} 2 "checkpoint checksum mismatch" --
                 $<TARGET_FILE:dem2d> run ${CMAKE_SOURCE_DIR}/tests/lib/fixtures/restart_disks.toml -q
                 --out ${CMAKE_CURRENT_BINARY_DIR}/inputs_checkpoint_damaged
                 --restart ${CMAKE_SOURCE_DIR}/fuzz/regression/checkpoint/crafted0.bin)
add_test(NAME "inputs: a file that is no checkpoint is exit status 2"
         COMMAND ${DEM2D_EXPECT} 2 "not a dem2d checkpoint" --
                 $<TARGET_FILE:dem2d> run ${CMAKE_SOURCE_DIR}/tests/lib/fixtures/restart_disks.toml -q
                 --out ${CMAKE_CURRENT_BINARY_DIR}/inputs_checkpoint_text
                 --start-from ${CMAKE_SOURCE_DIR}/tests/lib/fixtures/minimal.toml)
set_tests_properties("inputs: dem2d schema validates every case and refuses planted wrong ones as the reader does"
                     "inputs: a damaged checkpoint is exit status 2"
                     "inputs: a file that is no checkpoint is exit status 2"
                     PROPERTIES LABELS unit TIMEOUT 300)
