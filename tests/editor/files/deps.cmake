# test_editor_files: files that never lose work -- saves killed at random
# moments, autosave and recovery, files from a newer format version refused.
# Plain C++ (no Vulkan, no window), so the sanitizer suite runs it too.
set(TEST_DEPS facial_editor_model facial eng_scene)
