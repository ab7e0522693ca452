# test_soak: many frames of a crowd of animated faces (random state-machine
# triggers and parameter changes) rendered headless: memory flat, weights
# finite, no validation message. FACIAL_SOAK_FRAMES sets the length (the
# ctest entry runs the short default; the long run is done by hand).
set(TEST_DEPS facial facial_importers eng_scene eng_vk)
