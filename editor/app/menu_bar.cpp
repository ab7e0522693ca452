#include "editor/app/menu_bar.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>

#include "editor/app/tooltip.h"

namespace editor {

namespace {

constexpr const char* kPromptTitles[] = {"", "Open project", "Save project as", "Export .glb", "Export GIF", "Export video"};
constexpr const char* kPromptDefaults[] = {"", "project.json", "project.json", "export.glb", "clip.gif", "clip.mp4"};

bool ctrlKey(int key, bool shift = false, bool alt = false) {
  const ImGuiIO& io = ImGui::GetIO();
  return io.KeyCtrl && io.KeyShift == shift && io.KeyAlt == alt && !io.WantTextInput && ImGui::IsKeyPressed(key, false);
}

// A menu item with its shortcut listed and its hover help.
bool menuItem(const char* label, const char* shortcut, const char* help, bool enabled = true) {
  const bool chosen = ImGui::MenuItem(label, shortcut, false, enabled);
  tooltip(help);
  return chosen;
}

}  // namespace

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
    if (menuItem("New", "Ctrl+N", "Start an untitled project (unsaved changes stay in the autosaves)")) chosen.command = MenuCommand::New;
    if (menuItem("Open...", "Ctrl+O", "Open a project file (JSON): its clip, graph, sculpted targets and view"))
      ask(Prompt::Open, kPromptDefaults[int(Prompt::Open)]);
    if (ImGui::BeginMenu("Recent", state.recent && !state.recent->empty())) {
      for (const std::filesystem::path& path : *state.recent)
        if (menuItem(path.filename().string().c_str(), nullptr, path.string().c_str())) chosen = {MenuCommand::Open, path.string()};
      ImGui::EndMenu();
    }
    if (menuItem("Save", "Ctrl+S", "Save the project with its clip, sculpted model and edited graph beside it"))
      chosen.command = MenuCommand::Save;
    if (menuItem("Save As...", "Ctrl+Shift+S", "Save the project under a new file name"))
      ask(Prompt::SaveAs, kPromptDefaults[int(Prompt::SaveAs)]);
    ImGui::Separator();
    if (menuItem("Export .glb...", "Ctrl+E", "The face, its sculpted targets and every clip as glTF weight animations in one file"))
      ask(Prompt::ExportGlb, kPromptDefaults[int(Prompt::ExportGlb)]);
    if (menuItem("Export GIF...", "Ctrl+Shift+E", "The clip being edited as an animated GIF (20 frames/s, 384x384, the view on screen)"))
      ask(Prompt::ExportGif, kPromptDefaults[int(Prompt::ExportGif)]);
    if (menuItem("Export video...", "Ctrl+Alt+E", "The clip being edited as an H.264 MP4 (30 frames/s, 384x384, the view on screen, no sound)"))
      ask(Prompt::ExportVideo, kPromptDefaults[int(Prompt::ExportVideo)]);
    ImGui::Separator();
    if (menuItem("Quit", "Ctrl+Q", "Close the editor (with unsaved changes it asks first)")) chosen.command = MenuCommand::Quit;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (menuItem("Undo", "Ctrl+Z", "Undo the last timeline edit", state.canUndo)) chosen.command = MenuCommand::Undo;
    if (menuItem("Redo", "Ctrl+Y", "Redo the timeline edit undone last", state.canRedo)) chosen.command = MenuCommand::Redo;
    ImGui::Separator();
    // The dope sheet's keys (its own Ctrl+C / V / D / A do the same while no text field has focus).
    if (menuItem("Copy keys", "Ctrl+C", "Copy the selected keys of the dope sheet", state.hasSelection)) chosen.command = MenuCommand::Copy;
    if (menuItem("Paste keys at playhead", "Ctrl+V", "Paste the copied keys, the first at the playhead (missing tracks are made)",
                 state.hasClipboard))
      chosen.command = MenuCommand::Paste;
    if (menuItem("Duplicate keys", "Ctrl+D", "Copy the selected keys one frame after the selection", state.hasSelection))
      chosen.command = MenuCommand::Duplicate;
    if (menuItem("Select all keys", "Ctrl+A", "Select every key of every track")) chosen.command = MenuCommand::SelectAll;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (menuItem("Frame head / whole model", "F", "Frame the head, or the whole model")) chosen.command = MenuCommand::ToggleFraming;
    if (menuItem("Screenshot", "F12", "Write the window as a PNG (facial-editor.png, or --screenshot's path)"))
      chosen.command = MenuCommand::Screenshot;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (menuItem("Keys and files", nullptr, "The mouse and keyboard habits, and what the files hold")) showHelp_ = true;
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
  if (ctrlKey(GLFW_KEY_E, false, true)) return ask(Prompt::ExportVideo, kPromptDefaults[int(Prompt::ExportVideo)]);
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
  tooltip("Do it with this path (Enter)");
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false);
  tooltip("Close without doing it (Escape)");
  if ((ok && path_[0]) || cancel) {
    if (ok && path_[0]) {
      constexpr MenuCommand kCommands[] = {MenuCommand::None, MenuCommand::Open, MenuCommand::SaveAs, MenuCommand::ExportGlb,
                                           MenuCommand::ExportGif, MenuCommand::ExportVideo};
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
