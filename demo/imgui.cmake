# The window demo's panel: Dear ImGui (Debian's libimgui.a, GLFW + Vulkan
# backends included) on facial_cli. Included from demo/CMakeLists.txt.
target_link_libraries(facial_cli PRIVATE imgui glfw)
target_include_directories(facial_cli PRIVATE /usr/include/imgui)
