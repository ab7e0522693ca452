set(TEST_DEPS eng_vk eng_scene)
