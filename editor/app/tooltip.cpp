#include "editor/app/tooltip.h"

#include <imgui.h>
#include <imgui_internal.h>

namespace editor {

void tooltip(const char* text, float delaySeconds) {
  if (!text || !text[0] || !ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
  // HoveredIdTimer: how long the hovered widget has been under the mouse (disabled widgets have none: no delay).
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  if (delaySeconds > 0.0f && g.HoveredId != 0 && g.HoveredIdTimer < delaySeconds) return;
  ImGui::SetTooltip("%s", text);
}

}  // namespace editor
