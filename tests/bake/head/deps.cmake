set(TEST_DEPS facial_bake facial eng_scene)
