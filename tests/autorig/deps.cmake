set(TEST_DEPS facial_autorig facial_bake facial eng_scene)
