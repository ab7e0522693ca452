set(TEST_DEPS eng_scene)
