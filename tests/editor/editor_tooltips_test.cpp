// Tooltips on every control (issue 34, point 7): the editor's panels are
// checked on their sources, as tools/long_functions.py checks function
// lengths. Every ImGui control (button, check box, combo, slider, drag, text
// field, selectable, menu item, tab, canvas) must be followed by a call of the
// one tooltip helper (editor/app/tooltip.h) before the next control, and no
// panel calls ImGui::SetTooltip itself. What a hover shows over a key is
// tested with the curve model (CurveKeyMode.AKeysHoverTextSaysWhereItIs).
#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

struct TooltipAudit {
  size_t controls = 0;
  std::vector<std::string> missing;  // "LINE: CALL" for each control without a tooltip call before the next control
};

TooltipAudit auditTooltips(const std::string& source) {
  static const std::regex control(
      R"(ImGui::(Button|SmallButton|ArrowButton|InvisibleButton|Checkbox|RadioButton|Combo|BeginCombo|Slider\w*|VSlider\w*|)"
      R"(Drag\w*|Input\w*|Selectable|MenuItem|BeginTabItem|ColorEdit\w*|ColorPicker\w*|CollapsingHeader|TreeNode\w*)\()");
  static const std::regex tip(R"(\btooltip\w*\()");
  std::vector<std::smatch> calls;
  for (auto it = std::sregex_iterator(source.begin(), source.end(), control); it != std::sregex_iterator(); ++it) calls.push_back(*it);
  TooltipAudit audit{.controls = calls.size()};
  for (size_t i = 0; i < calls.size(); ++i) {
    const auto from = source.begin() + calls[i].position() + calls[i].length();
    const auto to = i + 1 < calls.size() ? source.begin() + calls[i + 1].position() : source.end();
    if (std::regex_search(from, to, tip)) continue;
    const auto at = source.begin() + calls[i].position();
    const size_t line = size_t(std::count(source.begin(), at, '\n')) + 1;
    audit.missing.push_back(std::to_string(line) + ": " + std::string(at, std::find(at, source.end(), '\n')));
  }
  return audit;
}

std::vector<fs::path> editorAppSources() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(testing_support::sourceDir() / "editor" / "app"))
    if (entry.path().extension() == ".cpp") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(EditorTooltips, TheCheckFindsAControlWithoutOne) {
  const std::string panel =
      "  if (ImGui::Button(\"Open\")) open(path_);\n"
      "  tooltip(\"Open the file\");\n"
      "  ImGui::Checkbox(\"snap\", &snap);\n"  // none
      "  if (ImGui::SmallButton(\"M\")) mute();\n"
      "  tooltipForCanvas(view);\n";
  const TooltipAudit audit = auditTooltips(panel);
  EXPECT_EQ(audit.controls, 3u);
  const std::vector<std::string>& missing = audit.missing;
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0], "3: ImGui::Checkbox(\"snap\", &snap);");
}

TEST(EditorTooltips, EveryControlOfEveryPanelHasOne) {
  const std::vector<fs::path> files = editorAppSources();
  ASSERT_GE(files.size(), 10u) << "editor/app/*.cpp not found under " << testing_support::sourceDir();
  size_t controls = 0;
  for (const fs::path& file : files) {
    const std::string source = testing_support::readTextFile(file);
    const TooltipAudit audit = auditTooltips(source);
    for (const std::string& missing : audit.missing)
      ADD_FAILURE() << file.filename().string() << ":" << missing << "  <- no tooltip() after this control";
    controls += audit.controls;
    // One home: the helper shows them all (and keeps them non-empty).
    if (file.filename() != "tooltip.cpp") {
      EXPECT_EQ(source.find("SetTooltip"), std::string::npos) << file.filename().string() << " calls ImGui::SetTooltip: use tooltip()";
    }
    EXPECT_EQ(source.find("tooltip(\"\")"), std::string::npos) << file.filename().string() << " has an empty tooltip";
  }
  EXPECT_GT(controls, 100u) << "the panels' controls were read";
}

}  // namespace
