# test_facial_speech: lip sync (facial/runtime/speech); the sampling job's no-allocation test counts allocations.
set(TEST_DEPS facial allocation_counter)
