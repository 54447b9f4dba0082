# Runs bench/plot_cost.py on the JSON that bench_kernels_smoke wrote and checks that it draws one
# PNG per scene. Usage: cmake -DPYTHON=<python3> -DSCRIPT=<plot_cost.py> -DJSON=<json>
#                            -DPREFIX=<png prefix> -P plot_smoke_test.cmake
foreach(scene plates hairball blob)
  file(REMOVE "${PREFIX}_${scene}.png")
endforeach()
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" "${JSON}" --out "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plot_cost.py exited with ${rc}\n${out}\n${err}")
endif()
foreach(scene plates hairball blob)
  set(png "${PREFIX}_${scene}.png")
  if(NOT EXISTS "${png}")
    message(FATAL_ERROR "plot_cost.py wrote no ${png}\n${out}\n${err}")
  endif()
  file(READ "${png}" magic LIMIT 4 HEX)
  if(NOT magic STREQUAL "89504e47")
    message(FATAL_ERROR "${png} is not a PNG file (starts with ${magic})")
  endif()
endforeach()
message(STATUS "plot_cost.py: one PNG per scene")
