set(TEST_DEPS eng_image)
