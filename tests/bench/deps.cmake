# Libraries the benchmarks in tests/bench/ link (read by CMakeLists.txt here).
# tests/CMakeLists.txt's per-area loop also reads it, because it turns this
# folder into a test_bench executable like any other area: with these
# libraries and gtest_main's main() that binary links and simply holds no tests.
# Benchmark files therefore never define main() (no BENCHMARK_MAIN()).
find_package(benchmark REQUIRED)
set(TEST_DEPS benchmark::benchmark facial eng_scene eng_vk allocation_counter)
if(TARGET facial_bake)
  list(APPEND TEST_DEPS facial_bake)
endif()
