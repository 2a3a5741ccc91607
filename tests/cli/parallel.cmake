# A film sharded over jobs by an existing scheduler, here GNU parallel on
# this machine (docs/films.md; a Slurm job array splits the same way):
# frame ranges 0:3 and 3:6 run as two parallel jobs into one directory; the
# frames are named by their global number, so merging is nothing to do; each
# is the same image, bit for bit, as the one a single run makes (frames are
# deterministic: the camera of frame k depends on k alone).
#   -DSOLRENDER=path -DIDIFF=path -DPARALLEL=path -DWORK_DIR=dir
if(NOT PARALLEL)
  message(FATAL_ERROR "GNU parallel not found (Debian: parallel)")
endif()
set(dir ${WORK_DIR}/sharded)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir}/jobs ${dir}/single)
file(WRITE ${dir}/path.json "{\"segments\": [{\"walk\": \"forward\", \"distance\": 1, \"duration\": 1}, {\"turn\": \"yaw\", \"degrees\": 30, \"duration\": 0.25}]}")
set(common --scene lattice-balls --path ${dir}/path.json --fps 4 --width 40 --height 30)
execute_process(COMMAND ${PARALLEL} --will-cite -j 2 --halt now,fail=1 ${SOLRENDER} ${common} -o ${dir}/jobs/frame-%03d.png
    --frames {} ::: 0:3 3:6
  RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the parallel jobs failed (${status}):\n${err}")
endif()
execute_process(COMMAND ${SOLRENDER} ${common} -o ${dir}/single/frame-%03d.png RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT err MATCHES "frames 0\\.\\.5 at 4 fps")
  message(FATAL_ERROR "the single run failed (${status}):\n${err}")
endif()
foreach(k 000 001 002 003 004 005)
  execute_process(COMMAND ${IDIFF} -fail 0 ${dir}/jobs/frame-${k}.png ${dir}/single/frame-${k}.png
    RESULT_VARIABLE same OUTPUT_VARIABLE out)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "frame ${k} of the sharded film differs from the single run's:\n${out}")
  endif()
endforeach()
