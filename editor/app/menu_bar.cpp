#include "editor/app/menu_bar.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>

namespace editor {

namespace {

constexpr const char* kPromptTitles[] = {"", "Open project", "Save project as", "Export .glb", "Export GIF"};
constexpr const char* kPromptDefaults[] = {"", "project.json", "project.json", "export.glb", "clip.gif"};

bool ctrlKey(int key, bool shift = false) {
  const ImGuiIO& io = ImGui::GetIO();
  return io.KeyCtrl && io.KeyShift == shift && !io.WantTextInput && ImGui::IsKeyPressed(key, false);
}

}  // namespace

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

MenuRequest MenuBar::ask(Prompt prompt, const char* path) {
  prompt_ = prompt;
  promptOpening_ = true;
  std::snprintf(path_, sizeof path_, "%s", path);
  return {};
}

MenuRequest MenuBar::draw(const MenuState& state) {
  MenuRequest chosen = drawMenus(state);
  if (chosen.command == MenuCommand::None) chosen = shortcuts(state);
  if (chosen.command == MenuCommand::None) chosen = drawPrompt();
  if (chosen.command == MenuCommand::None) chosen = drawQuitQuestion(state);
  if (chosen.command == MenuCommand::Save && !state.hasProjectFile) chosen = ask(Prompt::SaveAs, kPromptDefaults[int(Prompt::SaveAs)]);
  if (chosen.command == MenuCommand::Quit && state.dirty) {
    askToQuit();
    chosen = {};
  }
  if (showHelp_) {
    ImGui::SetNextWindowSize({440, 0}, ImGuiCond_Appearing);
    if (ImGui::Begin("About facial editor", &showHelp_, ImGuiWindowFlags_NoCollapse)) {
      ImGui::TextWrapped(
          "Drag in the view: orbit. Wheel: zoom. F: head / whole model. F12: screenshot.\n"
          "Timeline: Space play, Delete, Ctrl+Z / Ctrl+Y.\n"
          "File > Save writes the project (JSON) with its clip and sculpted model beside it; "
          "Export .glb writes the face, its sculpted targets and every clip as glTF weight animations.\n"
          "Every action has a --script form (docs/editor.md).");
    }
    ImGui::End();
  }
  return chosen;
}

MenuRequest MenuBar::drawMenus(const MenuState& state) {
  MenuRequest chosen;
  if (!ImGui::BeginMainMenuBar()) return chosen;
  height_ = ImGui::GetWindowSize().y;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New", "Ctrl+N")) chosen.command = MenuCommand::New;
    if (ImGui::MenuItem("Open...", "Ctrl+O")) ask(Prompt::Open, kPromptDefaults[int(Prompt::Open)]);
    if (ImGui::BeginMenu("Recent", state.recent && !state.recent->empty())) {
      for (const std::filesystem::path& path : *state.recent)
        if (ImGui::MenuItem(path.filename().string().c_str())) chosen = {MenuCommand::Open, path.string()};
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Save", "Ctrl+S")) chosen.command = MenuCommand::Save;
    if (ImGui::MenuItem("Save As...", "Ctrl+Shift+S")) ask(Prompt::SaveAs, kPromptDefaults[int(Prompt::SaveAs)]);
    ImGui::Separator();
    if (ImGui::MenuItem("Export .glb...", "Ctrl+E")) ask(Prompt::ExportGlb, kPromptDefaults[int(Prompt::ExportGlb)]);
    if (ImGui::MenuItem("Export GIF...", "Ctrl+Shift+E")) ask(Prompt::ExportGif, kPromptDefaults[int(Prompt::ExportGif)]);
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) chosen.command = MenuCommand::Quit;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (ImGui::MenuItem("Undo", "Ctrl+Z", false, state.canUndo)) chosen.command = MenuCommand::Undo;
    if (ImGui::MenuItem("Redo", "Ctrl+Y", false, state.canRedo)) chosen.command = MenuCommand::Redo;
    ImGui::Separator();
    // The dope sheet's keys (its own Ctrl+C / V / D / A do the same while no text field has focus).
    if (ImGui::MenuItem("Copy keys", "Ctrl+C", false, state.hasSelection)) chosen.command = MenuCommand::Copy;
    if (ImGui::MenuItem("Paste keys at playhead", "Ctrl+V", false, state.hasClipboard)) chosen.command = MenuCommand::Paste;
    if (ImGui::MenuItem("Duplicate keys", "Ctrl+D", false, state.hasSelection)) chosen.command = MenuCommand::Duplicate;
    if (ImGui::MenuItem("Select all keys", "Ctrl+A")) chosen.command = MenuCommand::SelectAll;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Frame head / whole model", "F")) chosen.command = MenuCommand::ToggleFraming;
    if (ImGui::MenuItem("Screenshot", "F12")) chosen.command = MenuCommand::Screenshot;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Keys and files")) showHelp_ = true;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
  return chosen;
}

MenuRequest MenuBar::shortcuts(const MenuState&) {
  if (ctrlKey(GLFW_KEY_N)) return {MenuCommand::New, {}};
  if (ctrlKey(GLFW_KEY_O)) return ask(Prompt::Open, kPromptDefaults[int(Prompt::Open)]);
  if (ctrlKey(GLFW_KEY_S)) return {MenuCommand::Save, {}};
  if (ctrlKey(GLFW_KEY_S, true)) return ask(Prompt::SaveAs, kPromptDefaults[int(Prompt::SaveAs)]);
  if (ctrlKey(GLFW_KEY_E)) return ask(Prompt::ExportGlb, kPromptDefaults[int(Prompt::ExportGlb)]);
  if (ctrlKey(GLFW_KEY_E, true)) return ask(Prompt::ExportGif, kPromptDefaults[int(Prompt::ExportGif)]);
  if (ctrlKey(GLFW_KEY_Q)) return {MenuCommand::Quit, {}};
  return {};
}

MenuRequest MenuBar::drawPrompt() {
  if (prompt_ == Prompt::None) return {};
  const char* title = kPromptTitles[int(prompt_)];
  if (promptOpening_) {
    ImGui::OpenPopup(title);
    promptOpening_ = false;
  }
  MenuRequest chosen;
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    prompt_ = Prompt::None;  // closed from outside
    return chosen;
  }
  ImGui::SetNextItemWidth(420.0f);
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  const bool entered = ImGui::InputText("##path", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue);
  tooltip("A path relative to the folder the editor was started in, or absolute");
  const bool ok = ImGui::Button("OK") || entered;
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false);
  if ((ok && path_[0]) || cancel) {
    if (ok && path_[0]) {
      constexpr MenuCommand kCommands[] = {MenuCommand::None, MenuCommand::Open, MenuCommand::SaveAs, MenuCommand::ExportGlb,
                                           MenuCommand::ExportGif};
      chosen = {kCommands[int(prompt_)], path_};
      if (prompt_ == Prompt::SaveAs && quitAfterSaveAs_) chosen.command = MenuCommand::QuitSave;
    }
    quitAfterSaveAs_ = false;
    prompt_ = Prompt::None;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return chosen;
}

MenuRequest MenuBar::drawQuitQuestion(const MenuState& state) {
  constexpr const char* kTitle = "Unsaved changes";
  if (quitAsked_) {
    ImGui::OpenPopup(kTitle);
    quitAsked_ = false;
  }
  MenuRequest chosen;
  if (!ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return chosen;
  ImGui::TextUnformatted("The project has unsaved changes. Save them before quitting?");
  if (ImGui::Button("Save")) {
    if (state.hasProjectFile) {
      chosen.command = MenuCommand::QuitSave;
    } else {  // an untitled project needs a file first: Save As, then quit
      ImGui::CloseCurrentPopup();
      ask(Prompt::SaveAs, kPromptDefaults[int(Prompt::SaveAs)]);
      quitAfterSaveAs_ = true;
    }
  }
  tooltip("Save the project, then quit");
  ImGui::SameLine();
  if (ImGui::Button("Discard")) chosen.command = MenuCommand::QuitDiscard;
  tooltip("Quit and drop the changes (and their autosave)");
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) ImGui::CloseCurrentPopup();
  tooltip("Keep editing");
  if (chosen.command != MenuCommand::None) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return chosen;
}

}  // namespace editor
