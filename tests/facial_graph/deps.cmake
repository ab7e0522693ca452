# test_facial_graph: the animation graph (facial) and glTF timeline import/export (facial_bake).
set(TEST_DEPS facial facial_bake eng_scene allocation_counter)
