# test_cli: the `facial express / sheet / rig` commands, run as the built
# program (exit codes, messages, golden contact sheets), and their shared
# FaceSetup, linked from facial_app (app/) for direct tests.
set(TEST_DEPS facial_app)
add_dependencies(test_cli facial_cli)
