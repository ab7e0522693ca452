# test_facial_rig: RBF, expression presets, rig mappings, CANDIDE/VRM import, faces speaking
# (the autorig: faces without targets made to speak).
set(TEST_DEPS facial facial_bake facial_importers facial_autorig)
