#include "engine/image/contact_sheet.h"

#include <algorithm>

#include "engine/image/text.h"

namespace eng {

Result<Canvas> composeContactSheet(const std::vector<ContactSheetTile>& tiles, const ContactSheetOptions& options) {
  if (tiles.empty()) return makeError(ErrorKind::InvalidArgument, "contact sheet: no tiles");
  if (options.columns < 1) return makeError(ErrorKind::InvalidArgument, "contact sheet: columns must be >= 1");
  const int tileW = tiles.front().image.width, tileH = tiles.front().image.height;
  for (size_t i = 1; i < tiles.size(); ++i)
    if (tiles[i].image.width != tileW || tiles[i].image.height != tileH)
      return makeError(ErrorKind::InvalidArgument, "contact sheet: tile " + std::to_string(i) + " is " + std::to_string(tiles[i].image.width) +
                       "x" + std::to_string(tiles[i].image.height) + ", expected " + std::to_string(tileW) + "x" +
                       std::to_string(tileH));
  Result<TextRenderer> text = TextRenderer::create();
  if (!text) return text.error();

  const int columns = std::min<int>(options.columns, static_cast<int>(tiles.size()));
  const int rows = static_cast<int>((tiles.size() + columns - 1) / columns);
  const int labelBand = static_cast<int>(options.labelHeight * 1.5f);
  const int titleBand = options.title.empty() ? 0 : static_cast<int>(options.labelHeight * 2.0f);
  const int cellW = tileW + options.padding, cellH = tileH + labelBand + options.padding;
  Canvas sheet(columns * cellW + options.padding, titleBand + rows * cellH + options.padding, options.background);

  if (!options.title.empty()) {
    const float size = options.labelHeight * 1.2f;
    text->draw(sheet, options.title, (sheet.width - text->measure(options.title, size)) / 2,
               static_cast<int>(options.labelHeight * 0.4f), size, options.labelColour);
  }
  for (size_t i = 0; i < tiles.size(); ++i) {
    const int col = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
    const int x = options.padding + col * cellW, y = titleBand + options.padding + row * cellH;
    sheet.blit(tiles[i].image.rgba, tileW, tileH, x, y);
    const int labelW = text->measure(tiles[i].label, options.labelHeight);
    text->draw(sheet, tiles[i].label, x + (tileW - labelW) / 2, y + tileH + labelBand / 6, options.labelHeight,
               options.labelColour);
  }
  return sheet;
}

}  // namespace eng
