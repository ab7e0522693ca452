# The tests write audio and reopen videos with libsndfile and libavformat
# themselves, and read Rhubarb's cues for ../shared/speech with nlohmann-json.
set(TEST_DEPS facial_audio PkgConfig::SNDFILE PkgConfig::FFMPEG nlohmann_json::nlohmann_json)
