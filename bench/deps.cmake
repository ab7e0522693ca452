# Libraries the benchmarks in bench/ link (read by CMakeLists.txt here).
# Benchmark files never define main() (benchmark_main provides it).
find_package(benchmark REQUIRED)
set(TEST_DEPS benchmark::benchmark facial facial_importers facial_autorig eng_scene eng_vk allocation_counter facial_audio facial_app facial_dataset)
if(TARGET facial_bake)
  list(APPEND TEST_DEPS facial_bake)
endif()
