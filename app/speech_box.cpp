#include "app/speech_box.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace app {
namespace {

template <size_t N>
void copyInto(std::array<char, N>& field, std::string_view text) {
  const size_t n = std::min(text.size(), N - 1);
  std::memcpy(field.data(), text.data(), n);
  field[n] = '\0';
}

}  // namespace

void SpeechBox::setText(std::string_view text) { copyInto(text_, text); }
void SpeechBox::setLanguage(std::string_view language) { copyInto(language_, language); }

void SpeechBox::show(std::string message, bool problem) {
  message_ = std::move(message);
  problem_ = problem;
}

void SpeechBox::reportProblem(const char* program, const std::string& problem) {
  show(problem, true);
  std::fprintf(stderr, "%s: %s\n", program, problem.c_str());
}

void SpeechBox::reportStarted(const char* program, const std::string& line, const std::vector<std::string>& notes) {
  std::printf("%s: speech: %s\n", program, line.c_str());
  std::fflush(stdout);
  for (const std::string& note : notes) std::fprintf(stderr, "%s: note: %s\n", program, note.c_str());
  show(notes.empty() ? std::string() : notes.back(), false);
}

SpeechBox::Action SpeechBox::draw(const Progress& progress, float width) {
  Action action = Action::None;
  const ImGuiStyle& style = ImGui::GetStyle();
  const float button = ImGui::CalcTextSize("Speak").x + 2.0f * style.FramePadding.x;
  ImGui::PushID("speech box");
  ImGui::SetNextItemWidth(std::max(60.0f, width - button - style.ItemSpacing.x));
  if (ImGui::InputTextWithHint("##text", "type a line to speak", text_.data(), text_.size(),
                               ImGuiInputTextFlags_EnterReturnsTrue))
    action = Action::Speak;
  ImGui::SameLine();
  if (ImGui::Button("Speak", {button, 0.0f})) action = Action::Speak;

  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("language");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::CalcTextSize("en-us-nyc").x + 2.0f * style.FramePadding.x);
  ImGui::InputText("##language", language_.data(), language_.size());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("an espeak-ng voice: en, en-us, vi, fr, de, es, ...");
  ImGui::SameLine();
  if (!progress.speaking) ImGui::BeginDisabled();
  if (ImGui::Button("Stop")) action = Action::Stop;
  if (!progress.speaking) ImGui::EndDisabled();
  // The line's progress, else the last message, on the Stop button's row: the
  // box keeps one height (the window demo frames the face beside its panel,
  // which would move with it). A message too long for the row ends in "..."
  // and shows whole when hovered.
  ImGui::SameLine();
  if (progress.speaking) {
    char overlay[48];
    std::snprintf(overlay, sizeof overlay, "%.1f / %.1f s", progress.time, progress.seconds);
    ImGui::ProgressBar(progress.seconds > 0.0f ? progress.time / progress.seconds : 0.0f, {-1.0f, 0.0f}, overlay);
  } else if (!message_.empty()) {
    const float room = ImGui::GetContentRegionAvail().x;
    std::string shown = message_;
    while (shown.size() > 1 && ImGui::CalcTextSize((shown + "...").c_str()).x > room) {
      shown.pop_back();
      while (!shown.empty() && (shown.back() & 0xC0) == 0x80) shown.pop_back();  // whole UTF-8 characters
    }
    if (shown.size() < message_.size()) shown += "...";
    const ImVec4 colour = problem_ ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : style.Colors[ImGuiCol_TextDisabled];
    ImGui::TextColored(colour, "%s", shown.c_str());
    if (shown.size() != message_.size() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", message_.c_str());
  } else {
    ImGui::NewLine();
  }
  ImGui::PopID();
  return action;
}

}  // namespace app
