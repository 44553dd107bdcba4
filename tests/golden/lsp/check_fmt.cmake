# `cncc fmt` on one file, through the command line: the output formats to
# itself, and `cncc --emit=ast` of the output equals that of the input once
# positions are dropped (so formatting never changes the checked tree).
# Called by CTest with -DCNCC= -DINPUT= -DWORK=.
file(MAKE_DIRECTORY ${WORK})
get_filename_component(name ${INPUT} NAME)
set(once ${WORK}/${name})

function(run output_variable)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "'${ARGN}' failed (${code}):\n${errors}")
  endif()
  set(${output_variable} "${output}" PARENT_SCOPE)
endfunction()

# The tree without positions, and without its first line (the file's path).
# The input's folder is an import path, so that the copy finds its imports.
get_filename_component(input_folder ${INPUT} DIRECTORY)
function(tree_of file output_variable)
  run(dump ${CNCC} --emit=ast -I ${input_folder} ${file})
  string(FIND "${dump}" "\n" first_line_end)
  math(EXPR rest_begin "${first_line_end} + 1")
  string(SUBSTRING "${dump}" ${rest_begin} -1 dump)
  string(REGEX REPLACE "[0-9]+:[0-9]+" "L:C" dump "${dump}")
  set(${output_variable} "${dump}" PARENT_SCOPE)
endfunction()

run(formatted ${CNCC} fmt ${INPUT})
file(WRITE ${once} "${formatted}")
run(twice ${CNCC} fmt ${once})
if(NOT twice STREQUAL formatted)
  message(FATAL_ERROR "formatting ${INPUT} twice changed it again; compare ${once}")
endif()
tree_of(${INPUT} before)
tree_of(${once} after)
string(LENGTH "${before}" length)
if(length LESS 100)
  message(FATAL_ERROR "--emit=ast printed almost nothing for ${INPUT}:\n${before}")
endif()
if(NOT before STREQUAL after)
  file(WRITE ${once}.before.ast "${before}")
  file(WRITE ${once}.after.ast "${after}")
  message(FATAL_ERROR "formatting changed the tree of ${INPUT}; see ${once}.*.ast")
endif()
