# test_cli: the `facial express / sheet / rig / say` commands, run as the built
# program (exit codes, messages, golden contact sheets), and their shared
# FaceSetup, linked from facial_app (app/) for direct tests. `say`'s videos are
# reopened with libavformat (through facial_audio's FFmpeg).
set(TEST_DEPS facial_app facial_audio PkgConfig::FFMPEG)
add_dependencies(test_cli facial_cli)
# Their tests read one sentence rendered to a video per process.
set(TEST_SUITES_IN_ONE_PROCESS SayCommand SaySync)
