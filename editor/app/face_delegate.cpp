#include "editor/app/face_delegate.h"

#include <imgui.h>

namespace editor {

const char* faceSourceName(FaceSource source) {
  switch (source) {
    case FaceSource::StateMachine: return "state machine";
    case FaceSource::ControlMap: return "control map";
    case FaceSource::Timeline: return "timeline";
    case FaceSource::BilinearPad: return "bilinear pad";
  }
  return "?";
}

void PanelMessage::draw() const {
  if (text.empty()) return;
  const ImVec4 colour = error ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.85f, 0.6f, 1.0f);
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(colour, "%s", text.c_str());
  ImGui::PopTextWrapPos();
}

}  // namespace editor
