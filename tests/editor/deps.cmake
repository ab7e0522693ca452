# test_editor: the editor's plain C++ models (timeline document, sculpt,
# picking) and, under xvfb-run, the built facial-editor program itself. Its
# exported videos (and GIFs) are read back with libavformat (facial_audio's FFmpeg).
set(TEST_DEPS facial_editor_model facial_app PkgConfig::FFMPEG)
add_dependencies(test_editor facial_cli)
if(TARGET facial_editor)
  add_dependencies(test_editor facial_editor)
endif()
