# test_facial_rig: RBF, expression presets, rig mappings, CANDIDE/VRM import.
set(TEST_DEPS facial facial_bake facial_importers)
