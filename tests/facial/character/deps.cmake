# test_facial_character: the character's life in the runtime (sway, breathing,
# saccades, lookAt), how a gaze reaches a rig (ARKit, FACS, VRM lookAt), and
# the embedding API (facial::Character, the C API) over them.
set(TEST_DEPS facial allocation_counter)
