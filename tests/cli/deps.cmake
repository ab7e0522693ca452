# test_cli: the `facial express / sheet / rig` commands, run as the built
# program (exit codes, messages, golden contact sheets), and their shared
# FaceSetup, compiled in for direct tests.
set(TEST_DEPS facial eng_scene)
target_sources(test_cli PRIVATE ${PROJECT_SOURCE_DIR}/demo/face_setup.cpp)
add_dependencies(test_cli facial_cli)
