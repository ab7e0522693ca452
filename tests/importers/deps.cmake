set(TEST_DEPS facial_importers facial eng_scene)
