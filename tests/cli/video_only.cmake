# solrender --video-only pipes each frame into ffmpeg as it renders and
# writes no frame file: the video decodes to exactly the frames of the video
# encoded the other way, from the PNG frames written to disk (an independent
# route: OpenImageIO's 8-bit quantisation, ffmpeg's PNG decoding; both feed
# x264 the same RGBA bytes, so their frames' MD5s agree); ffprobe counts the
# path's frames at the asked size; and the usages that make no sense are
# refused before any work.
#   -DSOLRENDER=path -DFFMPEG=path -DFFPROBE=path -DWORK_DIR=dir
set(dir ${WORK_DIR}/video-only)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir}/frames ${dir}/piped)
file(WRITE ${dir}/path.json "{\"segments\": [{\"walk\": \"forward\", \"distance\": 1, \"duration\": 1}]}")
set(film --device cpu --scene sandwich --path ${dir}/path.json --fps 6 --width 40 --height 30)
execute_process(COMMAND ${SOLRENDER} ${film} --video ${dir}/frames/v.mp4 -o ${dir}/frames/f-%02d.png
  RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "solrender --video (frames on disk) failed:\n${err}")
endif()
execute_process(COMMAND ${SOLRENDER} ${film} --video ${dir}/piped/v.mp4 --video-only RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT err MATCHES "frames piped as they rendered")
  message(FATAL_ERROR "solrender --video-only failed:\n${err}")
endif()
file(GLOB left ${dir}/piped/*)
if(NOT left STREQUAL "${dir}/piped/v.mp4")
  message(FATAL_ERROR "--video-only left more than the video: ${left}")
endif()
execute_process(COMMAND ${FFPROBE} -v error -count_frames -select_streams v:0
  -show_entries stream=nb_read_frames,width,height -of csv=p=0 ${dir}/piped/v.mp4 OUTPUT_VARIABLE probe)
string(STRIP "${probe}" probe)
if(NOT probe STREQUAL "40,30,7")  # 1 s at 6 fps: frames 0..6
  message(FATAL_ERROR "ffprobe of the piped video: '${probe}', expected 40,30,7")
endif()
foreach(which frames piped)
  execute_process(COMMAND ${FFMPEG} -v error -i ${dir}/${which}/v.mp4 -f framemd5 - OUTPUT_VARIABLE md5_${which})
  string(REGEX REPLACE "#[^\n]*\n" "" md5_${which} "${md5_${which}}")
endforeach()
if(NOT md5_piped STREQUAL md5_frames OR md5_piped STREQUAL "")
  message(FATAL_ERROR "the piped video's frames are not those of the video from the PNG frames:\n${md5_piped}\n--\n${md5_frames}")
endif()
# Frame files named with --video-only, and --video-only without a film: refused.
execute_process(COMMAND ${SOLRENDER} ${film} --video ${dir}/bad.mp4 --video-only -o ${dir}/x-%d.png
  RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 2 OR NOT err MATCHES "--video-only writes no frame files: leave out -o")
  message(FATAL_ERROR "--video-only with -o: expected exit 2 and its reason, got ${status}: ${err}")
endif()
execute_process(COMMAND ${SOLRENDER} --device cpu --video ${dir}/bad.mp4 --video-only RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 2 OR NOT err MATCHES "--video-only needs --path FILE and --video FILE")
  message(FATAL_ERROR "--video-only without --path: expected exit 2 and its reason, got ${status}: ${err}")
endif()
if(EXISTS ${dir}/bad.mp4)
  message(FATAL_ERROR "a refused --video-only left ${dir}/bad.mp4")
endif()
