# test_dataset: the dataset/ library (specs, seeded items, shards, landmarks on
# the morphed head, merge, batch manifests) and the `facial dataset` and
# `facial batch` commands run as the built program (tests/cli/cli_runner).
set(TEST_DEPS facial_dataset)
target_sources(test_dataset PRIVATE ${PROJECT_SOURCE_DIR}/tests/cli/cli_runner.cpp ${PROJECT_SOURCE_DIR}/tests/cli/cli_test_support.cpp)
add_dependencies(test_dataset facial_cli)
