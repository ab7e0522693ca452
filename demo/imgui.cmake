# The window demo's panel: Dear ImGui (Debian's libimgui.a, GLFW + Vulkan
# backends included). Included from demo/CMakeLists.txt.
target_link_libraries(facial_app PUBLIC imgui glfw)
target_include_directories(facial_app PUBLIC /usr/include/imgui)
