# The layout rules, checked on the sources (run by ctest as layout.Includes).
# Lower layers never include higher ones:
#   engine/core < engine/{scene,image} < engine/view < engine/vk/device
#     < engine/vk/draw < engine/vk/present      (the renderer; no emotions)
#   facial/      the component: engine/core only, no Vulkan, GLFW or ImGui
#   importers/   load-time importers: facial/ and engine/
#   bake/        offline builders: facial/, importers/, engine/
#   autorig/     targets made for faces without them: like bake/, no Vulkan
#   app/         what the program and the editor share
#   dataset/     labelled datasets, shards and batch jobs: above app/, for cli/ only
#   audio/       speech for the programs (GPL: espeak-ng, x264); no library includes it
#   cli/, editor/ the two programs, never each other
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

check_includes(facial "include[ \t]*[\"<]engine/(scene|vk|view|image|shaders)/" "facial/ may use engine/core only")
check_includes(facial "include[ \t]*[\"<](importers|bake|app|cli|editor|tests)/" "facial/ is the component, below the applications")
check_includes(facial "include[ \t]*[\"<](vulkan/|GLFW/|imgui)" "facial/ knows nothing of Vulkan or windows")
check_includes(engine "include[ \t]*[\"<](facial|importers|bake|app|cli|editor)/" "engine/ knows nothing of emotions")
check_includes(engine/core "include[ \t]*[\"<]engine/(scene|image|view|vk)/" "engine/core is the bottom layer")
check_includes(engine/scene "include[ \t]*[\"<]engine/(image|view|vk)/" "engine/scene is CPU scene data")
check_includes(engine/view "include[ \t]*[\"<](engine/vk/|vulkan/)" "engine/view is camera maths, no GPU")
check_includes(engine/vk/device "include[ \t]*[\"<]engine/vk/(draw|present)/" "engine/vk/device is below drawing and presentation")
check_includes(engine/vk/draw "include[ \t]*[\"<]engine/vk/present/" "engine/vk/draw knows nothing of windows")
check_includes(importers "include[ \t]*[\"<](bake|app|cli|editor)/" "importers/ is below the applications")
check_includes(bake "include[ \t]*[\"<](app|cli|editor)/" "bake/ is below the applications")
check_includes(autorig "include[ \t]*[\"<](engine/vk/|vulkan/|app/|cli/|editor/)" "autorig/ is an offline builder: no Vulkan, below the applications")
check_includes(app "include[ \t]*[\"<](cli|editor)/" "app/ is shared by cli/ and editor/")
foreach(library facial engine importers bake autorig)
  check_includes(${library} "include[ \t]*[\"<]audio/" "audio/ links GPL code: programs only")
endforeach()
check_includes(dataset "include[ \t]*[\"<](cli|editor|audio)/" "dataset/ is a program-side library below cli/")
foreach(library facial engine importers bake autorig app editor)
  check_includes(${library} "include[ \t]*[\"<]dataset/" "dataset/ sits above app/, for the program")
endforeach()
check_includes(audio "include[ \t]*[\"<](cli|editor)/" "audio/ is shared by the programs")
check_includes(editor "include[ \t]*[\"<]cli/" "editor/ and cli/ are separate programs")
check_includes(cli "include[ \t]*[\"<]editor/" "editor/ and cli/ are separate programs")

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layout rules broken:\n  ${text}")
endif()
message(STATUS "layout rules hold")
