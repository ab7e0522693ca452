# The layout rules, checked on the sources (run by ctest as layout.Includes):
#   facial/  the component: includes from engine/ only engine/core, nothing
#            from bake/, app/, demo/, editor/, and no Vulkan, GLFW or ImGui;
#   engine/  knows nothing of emotions: nothing from facial/, bake/, app/,
#            demo/ or editor/;
#   bake/    offline authoring: nothing from app/, demo/ or editor/;
#   app/     the application layer: nothing from demo/ or editor/.
# Usage: cmake -DSOURCE_DIR=<project root> -P layout_check.cmake
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "layout_check.cmake: pass -DSOURCE_DIR=<project root>")
endif()

set(violations "")

# Appends "file:line: #include X (why)" for every include in `dir` matching `pattern`.
function(check_includes dir pattern why)
  file(GLOB_RECURSE sources ${SOURCE_DIR}/${dir}/*.h ${SOURCE_DIR}/${dir}/*.hpp
                            ${SOURCE_DIR}/${dir}/*.c ${SOURCE_DIR}/${dir}/*.cpp)
  foreach(source ${sources})
    file(STRINGS ${source} lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line ${lines})
      if(line MATCHES "${pattern}")
        file(RELATIVE_PATH relative ${SOURCE_DIR} ${source})
        string(STRIP "${line}" line)
        list(APPEND violations "${relative}: ${line} (${why})")
      endif()
    endforeach()
  endforeach()
  set(violations ${violations} PARENT_SCOPE)
endfunction()

check_includes(facial "include[ \t]*[\"<]engine/(scene|vk|image|shaders)/" "facial/ may use engine/core only")
check_includes(facial "include[ \t]*[\"<](bake|app|demo|editor|tests)/" "facial/ is the component, below the applications")
check_includes(facial "include[ \t]*[\"<](vulkan/|GLFW/|imgui)" "facial/ knows nothing of Vulkan or windows")
check_includes(engine "include[ \t]*[\"<](facial|bake|app|demo|editor)/" "engine/ knows nothing of emotions")
check_includes(bake "include[ \t]*[\"<](app|demo|editor)/" "bake/ is below the applications")
check_includes(app "include[ \t]*[\"<](demo|editor)/" "app/ is shared by demo/ and editor/")

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layout rules broken:\n  ${text}")
endif()
message(STATUS "layout rules hold")
