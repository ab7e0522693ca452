set(TEST_DEPS eng_scene)
# The test runs the built program; make sure it is there.
add_dependencies(test_cli_demo_window facial_cli)
