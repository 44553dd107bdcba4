# The LLVM JIT backend: compiles a part's IR to native code with LLVM 14's
# ORC JIT. Optional: without LLVM 14 nothing here is built and the driver's
# `jit` target falls back to the IR interpreter.
# LLVMConfig.cmake runs C compile checks (FindFFI, FindTerminfo): it needs C.
get_property(jit_enabled_languages GLOBAL PROPERTY ENABLED_LANGUAGES)
if(NOT "C" IN_LIST jit_enabled_languages)
  include(CheckLanguage)
  check_language(C)
  if(NOT CMAKE_C_COMPILER)
    message(STATUS "no C compiler for LLVM's CMake package: the LLVM JIT is not built")
    return()
  endif()
  enable_language(C)
endif()
find_package(LLVM 14 CONFIG QUIET HINTS /usr/lib/llvm-14 /usr/lib/llvm-14/lib/cmake/llvm)
if(NOT LLVM_FOUND OR NOT TARGET LLVM)
  message(STATUS "LLVM 14 (shared libLLVM) not found: the LLVM JIT is not built")
  return()
endif()
message(STATUS "LLVM ${LLVM_PACKAGE_VERSION} found: building the LLVM JIT")

file(GLOB jit_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/llvm/src/*.cpp)
# Compiled once, position-independent, for both the static library and the
# loadable module.
add_library(cncc_jit_objects OBJECT ${jit_sources})
set_target_properties(cncc_jit_objects PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_include_directories(cncc_jit_objects PUBLIC ${CMAKE_CURRENT_LIST_DIR}/llvm/include)
# LLVM's headers do not build warning-free under our flags.
target_include_directories(cncc_jit_objects SYSTEM PRIVATE ${LLVM_INCLUDE_DIRS})
separate_arguments(jit_llvm_definitions NATIVE_COMMAND "${LLVM_DEFINITIONS}")
target_compile_definitions(cncc_jit_objects PRIVATE ${jit_llvm_definitions})
# An object library takes only cncc_ir's usage requirements (its headers).
target_link_libraries(cncc_jit_objects PUBLIC cncc_ir PRIVATE fmt::fmt)

# The static library, for the unit tests and benchmarks.
add_library(cncc_jit STATIC $<TARGET_OBJECTS:cncc_jit_objects>)
target_include_directories(cncc_jit PUBLIC ${CMAKE_CURRENT_LIST_DIR}/llvm/include)
# The shared libLLVM-14 (target LLVM), not the static component libraries:
# linking stays fast.
target_link_libraries(cncc_jit PUBLIC cncc_ir PRIVATE LLVM fmt::fmt)

# The module the driver loads when it runs the JIT (tools/cncc/jit_module.h),
# so that no other command loads LLVM. It holds no cncc_ir or cncc_geom: their
# symbols come from the executable that loads it (ENABLE_EXPORTS there).
add_library(cncc_jit_module MODULE $<TARGET_OBJECTS:cncc_jit_objects>)
set_target_properties(cncc_jit_module PROPERTIES PREFIX "" OUTPUT_NAME cncc_jit)
target_link_libraries(cncc_jit_module PRIVATE LLVM fmt::fmt)
