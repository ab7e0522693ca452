set(TEST_DEPS facial_app)
