# facial_app: the script format's own test (window_script_test.cpp).
set(TEST_DEPS eng_scene facial_app)
# The test runs the built program; make sure it is there.
add_dependencies(test_cli_demo_window facial_cli)
