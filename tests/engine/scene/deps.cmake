# The compressed-glTF tests encode their own files with the libraries the
# loader decodes with (meshoptimizer, libwebp, zlib for hand-made PNG streams).
find_package(meshoptimizer REQUIRED)
find_package(ZLIB REQUIRED)
pkg_check_modules(WEBP REQUIRED IMPORTED_TARGET libwebp)
# allocation_counter: the loader scaling test counts the allocations of a load.
set(TEST_DEPS facial_importers eng_scene nlohmann_json::nlohmann_json meshoptimizer::meshoptimizer PkgConfig::WEBP ZLIB::ZLIB
    allocation_counter)
