set(TEST_DEPS eng_scene eng_image)
# The tests run the built program; make sure it is there.
add_dependencies(test_cli_demo facial_cli)
