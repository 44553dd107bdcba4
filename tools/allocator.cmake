# The heap allocator of the executables (`cncc_allocator`, linked by cncc,
# cncc-lsp and the benchmarks). Checking a large file makes and frees
# hundreds of thousands of small objects (syntax nodes, declarations,
# values) on two threads; mimalloc (Debian's libmimalloc-dev) does that in
# far fewer instructions than the C library's malloc. Its shared library,
# linked before the C library, takes the place of malloc for the whole
# process. Without the package, or under the sanitizers (which bring their
# own allocator), the C library's malloc serves; so it does when configured
# with -DCMAKE_DISABLE_FIND_PACKAGE_mimalloc=ON, which valgrind's memcheck
# needs (it sees mimalloc's delete of the C++ library's new as mismatched).
add_library(cncc_allocator INTERFACE)
find_package(mimalloc 2.0 QUIET GLOBAL)
if(mimalloc_FOUND AND NOT CNCC_SANITIZE)
  target_link_libraries(cncc_allocator INTERFACE mimalloc)
  # Kept even when nothing calls it by name: it is there to replace malloc.
  target_link_options(cncc_allocator INTERFACE "LINKER:--push-state,--no-as-needed"
                      $<TARGET_FILE:mimalloc> "LINKER:--pop-state")
  message(STATUS "Allocator: mimalloc")
else()
  message(STATUS "Allocator: the C library's malloc")
endif()
