# test_facial_graph: the animation graph (facial); VRM material binds come from importers.
set(TEST_DEPS facial facial_importers eng_scene allocation_counter)
