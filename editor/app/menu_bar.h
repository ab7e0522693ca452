#pragma once
// The window's menu bar: File (New, Open, Save, Save As, Recent, Export .glb,
// Export GIF, Export video, Quit), Edit (Undo, Redo, and the dope sheet's Copy, Paste at the
// playhead, Duplicate, Select all), View (framing, screenshot) and Help,
// each item with its shortcut listed and the same shortcuts on the keyboard.
// ImGui has no file dialog, so Open, Save As and the exports ask for a path
// in a small modal. Quitting with unsaved changes asks Save / Discard /
// Cancel. The bar only says what was chosen (MenuRequest); the app does it.
#include <filesystem>
#include <string>
#include <vector>

namespace editor {

enum class MenuCommand {
  None, New, Open, Save, SaveAs, ExportGlb, ExportGif, ExportVideo, Quit, QuitSave, QuitDiscard,
  Undo, Redo, Copy, Paste, Duplicate, SelectAll, ToggleFraming, Screenshot,
};

struct MenuRequest {
  MenuCommand command = MenuCommand::None;
  std::string path;  // Open, SaveAs and the exports: the path typed or chosen from Recent
};

// What the menus show (greyed items, the recent list, the title's file).
struct MenuState {
  const std::vector<std::filesystem::path>* recent = nullptr;
  bool hasProjectFile = false;
  bool dirty = false;
  bool canUndo = false;
  bool canRedo = false;
  bool hasSelection = false;  // the dope sheet's keys: Copy, Duplicate
  bool hasClipboard = false;  // Paste
};

class MenuBar {
 public:
  // Draws the bar, the keyboard shortcuts and any open prompt; what the user chose this frame.
  MenuRequest draw(const MenuState& state);
  // Height of the bar as last drawn (the panels go below it).
  float height() const { return height_; }
  // The window's close button (or Quit) with unsaved changes: opens the Save / Discard / Cancel question.
  void askToQuit() { quitAsked_ = true; }

 private:
  enum class Prompt { None, Open, SaveAs, ExportGlb, ExportGif, ExportVideo };
  MenuRequest drawMenus(const MenuState& state);
  MenuRequest shortcuts(const MenuState& state);
  MenuRequest drawPrompt();
  MenuRequest drawQuitQuestion(const MenuState& state);
  MenuRequest ask(Prompt prompt, const char* path);

  float height_ = 0.0f;
  Prompt prompt_ = Prompt::None;
  bool promptOpening_ = false;
  bool quitAsked_ = false;
  bool quitAfterSaveAs_ = false;  // the quit question's Save on an untitled project
  bool showHelp_ = false;
  char path_[512] = {};
};

}  // namespace editor
