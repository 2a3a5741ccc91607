# A full disk (every write past 4 KB fails: bash's `ulimit -f 4` with
# SIGXFSZ ignored, so write() returns EFBIG as it returns ENOSPC on a full
# disk; no tmpfs needs mounting) loses nothing and says so: solrender's
# image and AOVs, a film's frames and solshape's meshes fail with a
# message and a non-zero status, the files that were there keep their
# bytes, no temporary is left, and a film counts no frame as done.
#   -DSOLRENDER=path -DSOLSHAPE=path (may be empty) -DBASH=path -DWORK_DIR=dir
set(dir ${WORK_DIR}/full-disk)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})

# Runs a command with the limit; it must fail naming the file.
function(run_full what)
  string(REPLACE ";" " " line "${ARGN}")
  execute_process(COMMAND ${BASH} -c "trap '' XFSZ; ulimit -f 4; exec ${line}" WORKING_DIRECTORY ${dir}
    RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(status EQUAL 0)
    message(FATAL_ERROR "${what}: exit status 0 on a full disk\n${err}")
  endif()
  if(NOT err MATCHES "cannot write: File too large")
    message(FATAL_ERROR "${what}: the message does not say why\n${err}")
  endif()
  message(STATUS "${what}: exit ${status}: ${err}")
endfunction()

# The files written with room, their bytes kept to compare.
set(image --device cpu --scene lattice-balls --width 64 --height 48)
foreach(name keep.png keep.jpg keep.exr)
  execute_process(COMMAND ${SOLRENDER} ${image} -o ${dir}/${name} RESULT_VARIABLE status ERROR_QUIET)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "solrender -o ${name} failed with room")
  endif()
  file(SHA256 ${dir}/${name} before_${name})
  file(SIZE ${dir}/${name} size)
  if(size LESS 4096)
    message(FATAL_ERROR "${name} is ${size} bytes: too small for the test")
  endif()
  run_full("solrender -o ${name}" ${SOLRENDER} ${image} -o ${dir}/${name})
  file(SHA256 ${dir}/${name} after)
  if(NOT after STREQUAL before_${name})
    message(FATAL_ERROR "solrender -o ${name} on a full disk changed the file that was there")
  endif()
endforeach()
# The image fits, its AOVs do not: neither is replaced.
run_full("solrender --aov" ${SOLRENDER} --device cpu --scene plane --width 48 --height 36 -o ${dir}/keep.png --aov ${dir}/keep.exr)
foreach(name keep.png keep.exr)
  file(SHA256 ${dir}/${name} after)
  if(NOT after STREQUAL before_${name})
    message(FATAL_ERROR "solrender --aov on a full disk changed ${name}")
  endif()
endforeach()
# A film: no frame is written, so none is skipped as done when it resumes
# (its manifest, frame-film.json, may fit where a frame does not).
file(WRITE ${dir}/path.json "{\"segments\": [{\"hold\": 0.5}]}")
run_full("solrender --path" ${SOLRENDER} ${image} --path ${dir}/path.json --fps 4 -o ${dir}/frame-%02d.png)
file(GLOB frames ${dir}/frame-[0-9]*)
if(frames)
  message(FATAL_ERROR "a film on a full disk left frames: ${frames}")
endif()
# solshape: a good mesh stays as it was.
if(SOLSHAPE)
  execute_process(COMMAND ${SOLSHAPE} sphere --radius 1 --resolution 8 -o ${dir}/s.ply RESULT_VARIABLE status ERROR_QUIET)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "solshape failed with room")
  endif()
  file(SHA256 ${dir}/s.ply before)
  run_full("solshape sphere" ${SOLSHAPE} sphere --radius 1 --resolution 8 -o ${dir}/s.ply)
  file(SHA256 ${dir}/s.ply after)
  if(NOT after STREQUAL before)
    message(FATAL_ERROR "solshape on a full disk changed the mesh that was there")
  endif()
endif()
# No temporary anywhere.
file(GLOB left ${dir}/.*)
if(left)
  message(FATAL_ERROR "temporaries left on a full disk: ${left}")
endif()
