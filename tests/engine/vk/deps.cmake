set(TEST_DEPS eng_vk facial_importers eng_scene)
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
  set_tests_properties(vk.WindowTestsUnderXvfb PROPERTIES ENVIRONMENT "FACIAL_VALIDATION=1" TIMEOUT 120)
  set(TEST_DISCOVERY_FILTER "-Window*")
endif()
