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
endif()

# Debian builds glslang without RTTI, so UBSan's vptr check (which reads the
# typeinfo of polymorphic classes) cannot be compiled against its classes.
# Call this on the one file that includes glslang headers.
function(facial_no_vptr_check source)
  if(FACIAL_SANITIZE)
    set_property(SOURCE ${source} APPEND PROPERTY COMPILE_OPTIONS -fno-sanitize=vptr)
  endif()
endfunction()
