# test_facial_json: JsonNode, the component's typed JSON reading.
set(TEST_DEPS facial)
