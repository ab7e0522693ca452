set(TEST_DEPS eng_view eng_scene)
