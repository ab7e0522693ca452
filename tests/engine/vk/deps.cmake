set(TEST_DEPS eng_vk facial_importers eng_scene X11::X11)
# Xlib's macros stay in the one file that reads the window back from the server.
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/x11_window_pixels.cpp PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
# They need a display: ctest runs them under a virtual X server as one entry,
# vk.WindowTestsUnderXvfb, and leaves them out of the per-test entries (run
# by hand without a display, they skip with a message).
# -noreset: Xvfb would otherwise reset when one test's window closes, and the
# next test could not connect.
find_program(XVFB_RUN xvfb-run)
if(XVFB_RUN)
  add_test(NAME vk.WindowTestsUnderXvfb
           COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24 -noreset" $<TARGET_FILE:test_engine_vk> --gtest_filter=Window*
           WORKING_DIRECTORY ${PROJECT_BINARY_DIR})
  set_tests_properties(vk.WindowTestsUnderXvfb PROPERTIES ENVIRONMENT "FACIAL_VALIDATION=1" TIMEOUT 120 COST ${FACIAL_LONG_TEST_COST})
  # The same through the Vulkan swapchain, which a CPU device leaves for X11 shared memory (what a GPU presents with).
  add_test(NAME vk.WindowTestsUnderXvfbThroughTheSwapchain
           COMMAND ${XVFB_RUN} -a -s "-screen 0 1024x768x24 -noreset" $<TARGET_FILE:test_engine_vk> --gtest_filter=Window*
           WORKING_DIRECTORY ${PROJECT_BINARY_DIR})
  set_tests_properties(vk.WindowTestsUnderXvfbThroughTheSwapchain PROPERTIES ENVIRONMENT "FACIAL_VALIDATION=1;FACIAL_X11_SHM=0" TIMEOUT 120 COST ${FACIAL_LONG_TEST_COST})
  set(TEST_DISCOVERY_FILTER "-Window*")
endif()
