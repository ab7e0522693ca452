#pragma once
// For looking at a dataset: an image with its 68 landmarks drawn on it (jaw
// yellow, brows orange, nose cyan, eyes green, lips red), to check by eye
// that the points sit on the rendered face.
#include <filesystem>

#include "dataset/landmark_tracker.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace dataset {

void drawLandmarks(eng::Image& image, const Landmarks2& landmarks);
eng::Result<void> makeOverlayFolder(const std::filesystem::path& folder);
// The image with its landmarks, written whole as PNG.
eng::Result<void> writeOverlay(eng::Image image, const Landmarks2& landmarks, const std::filesystem::path& path);

}  // namespace dataset
