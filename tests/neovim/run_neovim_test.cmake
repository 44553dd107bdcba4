# The Neovim test: runs lsp_client.lua in a headless Neovim whose built-in
# LSP client talks to the built cncc-lsp, then checks what the client
# received. Called by CTest with -DNVIM= -DSERVER= -DSOURCE_DIR= -DRESULT=.
# Without Neovim it prints "skipped:" (CTest's SKIP_REGULAR_EXPRESSION).
if(NOT NVIM)
  message("skipped: nvim is not installed (Debian package 'neovim')")
  return()
endif()

set(script ${SOURCE_DIR}/tests/neovim/lsp_client.lua)
set(document ${SOURCE_DIR}/tests/neovim/s_profile_with_error.cdl)
file(REMOVE ${RESULT})
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env CNCC_LSP=${SERVER} CNCC_NVIM_DOCUMENT=${document}
          CNCC_NVIM_RESULT=${RESULT} XDG_STATE_HOME=${RESULT}.state XDG_DATA_HOME=${RESULT}.data
          ${NVIM} --headless --clean -n -i NONE -u NONE -c "luafile ${script}"
  RESULT_VARIABLE exit_code
  OUTPUT_VARIABLE output
  ERROR_VARIABLE output
  TIMEOUT 60)
if(NOT EXISTS ${RESULT})
  message(FATAL_ERROR "nvim wrote no results (exit ${exit_code}):\n${output}")
endif()
file(READ ${RESULT} results)
message("Neovim received: ${results}")

# Fails the test unless `condition` (if() syntax, as a string) holds.
function(expect condition description)
  cmake_language(EVAL CODE "
    if(NOT (${condition}))
      message(FATAL_ERROR [==[expected ${description}]==])
    endif()")
endfunction()

string(JSON problem_count LENGTH "${results}" problems)
expect("problem_count EQUAL 0" "no problems")

# The diagnostic `cncc check` gives: weights-count at 9:42 (1-based).
string(JSON diagnostic_count LENGTH "${results}" diagnostics)
expect("diagnostic_count EQUAL 1" "exactly one diagnostic")
string(JSON code GET "${results}" diagnostics 0 code)
string(JSON message GET "${results}" diagnostics 0 message)
string(JSON line GET "${results}" diagnostics 0 line)
string(JSON column GET "${results}" diagnostics 0 column)
string(JSON severity GET "${results}" diagnostics 0 severity)
string(JSON source GET "${results}" diagnostics 0 source)
expect("code STREQUAL \"weights-count\"" "the code weights-count, got '${code}'")
expect("message STREQUAL \"'weights' has 6 entries but 'points' has 7\"" "the front end's message, got '${message}'")
expect("line EQUAL 8 AND column EQUAL 33" "the span at line 8, column 33 (0-based), got ${line}:${column}")
expect("severity EQUAL 1" "severity error (1), got ${severity}")
expect("source STREQUAL \"cncc\"" "source cncc")

string(JSON hover GET "${results}" hover)
string(FIND "${hover}" "nurbs(order=k | degree=p, points=L, weights=W?, knots=K?)" signature)
expect("signature GREATER -1" "the hover to show the nurbs signature, got '${hover}'")
string(FIND "${hover}" "rational B-spline" describes)
expect("describes GREATER -1" "the hover to describe nurbs")

string(JSON completion GET "${results}" completion)
foreach(label P depth w6 nurbs sin)
  string(FIND "${completion}" "\"${label}\"" found)
  expect("found GREATER -1" "'${label}' among the completions ${completion}")
endforeach()
string(FIND "${completion}" "\"tolerance\"" modifier)
expect("modifier EQUAL -1" "no modifier inside an argument list")
