# solrender --path reruns: a film's frames are one film's. A first run makes
# the output folder and writes the manifest beside the frames; a rerun with
# another size is refused before any frame (exit 2, naming the field) and
# leaves the frames as they were; --overwrite renders them again at the new
# size; frames without a manifest are refused; a bad --video name is refused
# before the first frame.
#   -DSOLRENDER=path -DWORK_DIR=dir
set(dir ${WORK_DIR}/film_rerun)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/hold.json "{\"segments\": [{\"hold\": 0.5}]}")
set(common --scene plane --device cpu --path ${dir}/hold.json --fps 4)

# The width of a PNG: bytes 16..19 of its header, big-endian.
function(png_width file out)
  file(READ ${file} hex OFFSET 16 LIMIT 4 HEX)
  math(EXPR width "0x${hex}")
  set(${out} ${width} PARENT_SCOPE)
endfunction()

function(run expect_status)
  execute_process(COMMAND ${SOLRENDER} ${ARGN} RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL expect_status)
    message(FATAL_ERROR "solrender ${ARGN}: exit ${status}, expected ${expect_status}:\n${err}")
  endif()
  set(err "${err}" PARENT_SCOPE)
endfunction()

# The folder out/ does not exist: it is made.
run(0 ${common} --width 8 --height 6 -o ${dir}/out/frame-%03d.png)
foreach(k 000 001 002)
  if(NOT EXISTS ${dir}/out/frame-${k}.png)
    message(FATAL_ERROR "frame ${k} is missing")
  endif()
endforeach()
if(NOT EXISTS ${dir}/out/frame-film.json)
  message(FATAL_ERROR "no manifest beside the frames")
endif()

# The same settings again: nothing to do.
run(0 ${common} --width 8 --height 6 -o ${dir}/out/frame-%03d.png)
if(NOT err MATCHES "0 rendered in [0-9.]+ s, 3 already there")
  message(FATAL_ERROR "the same film again rendered frames:\n${err}")
endif()

# Another size: refused, naming the field; the frames stay 8 wide.
run(2 ${common} --width 10 --height 6 -o ${dir}/out/frame-%03d.png)
if(NOT err MATCHES "the frames there were rendered with other settings \\(.*frame-film.json: width differs\\); --overwrite")
  message(FATAL_ERROR "the refusal does not name the width:\n${err}")
endif()
png_width(${dir}/out/frame-001.png width)
if(NOT width EQUAL 8)
  message(FATAL_ERROR "a refused rerun changed frame 1 (width ${width})")
endif()

# --overwrite: every frame again at the new size, and the manifest follows.
run(0 ${common} --width 10 --height 6 --overwrite -o ${dir}/out/frame-%03d.png)
foreach(k 000 001 002)
  png_width(${dir}/out/frame-${k}.png width)
  if(NOT width EQUAL 10)
    message(FATAL_ERROR "--overwrite left frame ${k} at width ${width}")
  endif()
endforeach()
run(0 ${common} --width 10 --height 6 -o ${dir}/out/frame-%03d.png)

# Frames without a manifest: their settings are unknown.
file(REMOVE ${dir}/out/frame-film.json)
run(2 ${common} --width 10 --height 6 -o ${dir}/out/frame-%03d.png)
if(NOT err MATCHES "frame-000.png is there without a film manifest")
  message(FATAL_ERROR "frames without a manifest were not refused:\n${err}")
endif()

# A --video name ffmpeg cannot write: refused before the first frame.
run(2 ${common} --width 8 --height 6 -o ${dir}/video/frame-%03d.png --video ${dir}/film.avi)
if(NOT err MATCHES "--video .*film.avi: give a .mp4, .mkv or .mov file" OR EXISTS ${dir}/video/frame-000.png)
  message(FATAL_ERROR "a bad --video name was not refused up front:\n${err}")
endif()
