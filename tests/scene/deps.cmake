set(TEST_DEPS eng_scene nlohmann_json::nlohmann_json)
