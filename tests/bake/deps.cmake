# allocation_counter: the timeline scaling test counts the allocations of an import.
set(TEST_DEPS facial_bake facial eng_scene allocation_counter)
