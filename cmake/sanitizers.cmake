# Sanitizer and fuzzing builds (issue 12). Both are off by default.
#
#   -DFACIAL_SANITIZE=ON  AddressSanitizer + UndefinedBehaviorSanitizer on every
#                         target (leak checking is on: LeakSanitizer runs at exit).
#                         Any UBSan report aborts (-fno-sanitize-recover), so a test
#                         that triggers one fails. Run the binaries with
#                         LSAN_OPTIONS=suppressions=tools/sanitizers/lsan.supp (the
#                         Vulkan driver's own leaks; see that file).
#   -DFACIAL_FUZZ=ON      also builds fuzz/ (libFuzzer, needs clang): every library
#                         gets -fsanitize=fuzzer-no-link (coverage feedback), the
#                         fuzzers link -fsanitize=fuzzer. Implies FACIAL_SANITIZE.
#                         The same build directory therefore serves the sanitizer
#                         test suite and the fuzzers (one compile of the libraries).
option(FACIAL_SANITIZE "Build everything with AddressSanitizer + UBSan (leak checking on)" OFF)
option(FACIAL_FUZZ "Build the libFuzzer targets in fuzz/ (clang only; implies FACIAL_SANITIZE)" OFF)

if(FACIAL_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "FACIAL_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  set(FACIAL_SANITIZE ON CACHE BOOL "" FORCE)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(FACIAL_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  # -O1 with line tables only (after the build type's -O2 -g, so they win):
  # reports need file:line, not variables, and this compiles much faster.
  add_compile_options(-O1 $<IF:$<CXX_COMPILER_ID:Clang>,-gline-tables-only,-g1>)
  add_link_options(-fsanitize=address,undefined)
  # LLVM's linker where there is one: the sanitized executables are large
  # and GNU ld took 78 s of a 2-core CI build linking them.
  find_program(FACIAL_LLD ld.lld)
  if(FACIAL_LLD AND CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    add_link_options(-fuse-ld=lld)
  endif()
endif()

# At -O1 clang leaves glm's and Eigen's small operators out of line, and the
# rigging's geometry loops call them millions of times: sanitized, a transfer
# of the built-in head took ten times as long as in the plain build. The
# targets and sources of such loops keep -O2 (it comes after -O1, so it
# wins); reports still name file and line.
#   facial_optimize_when_sanitized(TARGETS facial_autorig SOURCES runtime/rbf.cpp)
# In the fuzzing build they also leave out libFuzzer's comparison tracing
# (trace-cmp: a call per compared integer, a tenth of a sanitized transfer):
# the fuzzers feed parsers, and these loops branch on geometry, not on input
# bytes; their edges are still counted.
function(facial_optimize_when_sanitized)
  cmake_parse_arguments(ARG "" "" "TARGETS;SOURCES" ${ARGN})
  if(FACIAL_SANITIZE)
    set(options -O2)
    if(FACIAL_FUZZ)
      list(APPEND options -fno-sanitize-coverage=trace-cmp)
    endif()
    foreach(target IN LISTS ARG_TARGETS)
      target_compile_options(${target} PRIVATE ${options})
    endforeach()
    # A source with options of its own is compiled outside the unity batches.
    if(ARG_SOURCES)
      set_property(SOURCE ${ARG_SOURCES} APPEND PROPERTY COMPILE_OPTIONS ${options})
    endif()
  endif()
endfunction()

# Debian builds glslang without RTTI, so UBSan's vptr check (which reads the
# typeinfo of polymorphic classes) cannot be compiled against its classes.
# Call this on the one file that includes glslang headers.
function(facial_no_vptr_check source)
  if(FACIAL_SANITIZE)
    set_property(SOURCE ${source} APPEND PROPERTY COMPILE_OPTIONS -fno-sanitize=vptr)
  endif()
endfunction()
