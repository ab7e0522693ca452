#include "engine/image/text.h"

#include <fstream>
#include <iterator>
#include <vector>

// Private copy of the implementation: ImGui builds its own as static, so
// there is no symbol clash.
#define STB_TRUETYPE_IMPLEMENTATION
#define STBTT_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <imstb_truetype.h>
#pragma GCC diagnostic pop

namespace eng {

struct TextRenderer::Impl {
  std::vector<unsigned char> fontData;
  stbtt_fontinfo font{};
};

TextRenderer::TextRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TextRenderer::TextRenderer(TextRenderer&&) noexcept = default;
TextRenderer& TextRenderer::operator=(TextRenderer&&) noexcept = default;
TextRenderer::~TextRenderer() = default;

std::filesystem::path TextRenderer::defaultFontPath() {
  return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

Result<TextRenderer> TextRenderer::create(const std::filesystem::path& fontFile) {
  const std::filesystem::path path = fontFile.empty() ? defaultFontPath() : fontFile;
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorKind::Io, path.string() + ": cannot open font file (install fonts-dejavu-core)");
  auto impl = std::make_unique<Impl>();
  impl->fontData.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const int offset = stbtt_GetFontOffsetForIndex(impl->fontData.data(), 0);
  if (offset < 0 || !stbtt_InitFont(&impl->font, impl->fontData.data(), offset))
    return makeError(ErrorKind::Malformed, path.string() + ": not a TrueType font");
  return TextRenderer(std::move(impl));
}

int TextRenderer::measure(std::string_view text, float pixelHeight) const {
  const float scale = stbtt_ScaleForPixelHeight(&impl_->font, pixelHeight);
  float x = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    int advance = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&impl_->font, static_cast<unsigned char>(text[i]), &advance, &lsb);
    x += advance * scale;
    if (i + 1 < text.size())
      x += scale * stbtt_GetCodepointKernAdvance(&impl_->font, static_cast<unsigned char>(text[i]),
                                                 static_cast<unsigned char>(text[i + 1]));
  }
  return static_cast<int>(x + 0.5f);
}

void TextRenderer::draw(Canvas& canvas, std::string_view text, int x, int y, float pixelHeight,
                        glm::u8vec4 colour) const {
  const stbtt_fontinfo& font = impl_->font;
  const float scale = stbtt_ScaleForPixelHeight(&font, pixelHeight);
  int ascent = 0, descent = 0, lineGap = 0;
  stbtt_GetFontVMetrics(&font, &ascent, &descent, &lineGap);
  const int baseline = y + static_cast<int>(ascent * scale + 0.5f);
  float penX = static_cast<float>(x);
  std::vector<unsigned char> glyph;
  for (size_t i = 0; i < text.size(); ++i) {
    const int cp = static_cast<unsigned char>(text[i]);
    int advance = 0, lsb = 0;
    stbtt_GetCodepointHMetrics(&font, cp, &advance, &lsb);
    int x0, y0, x1, y1;
    stbtt_GetCodepointBitmapBox(&font, cp, scale, scale, &x0, &y0, &x1, &y1);
    const int gw = x1 - x0, gh = y1 - y0;
    if (gw > 0 && gh > 0) {
      glyph.assign(static_cast<size_t>(gw) * gh, 0);
      stbtt_MakeCodepointBitmap(&font, glyph.data(), gw, gh, gw, scale, scale, cp);
      const int ox = static_cast<int>(penX + 0.5f) + x0, oy = baseline + y0;
      for (int row = 0; row < gh; ++row) {
        const int py = oy + row;
        if (py < 0 || py >= canvas.height) continue;
        for (int col = 0; col < gw; ++col) {
          const int px = ox + col;
          if (px < 0 || px >= canvas.width) continue;
          const float a = glyph[static_cast<size_t>(row) * gw + col] / 255.0f * (colour.a / 255.0f);
          uint8_t* p = canvas.rgba.data() + (static_cast<size_t>(py) * canvas.width + px) * 4;
          // "Over" with straight alpha, so labels also show on a transparent canvas
          // (on an opaque one this is the plain mix).
          const float below = p[3] / 255.0f * (1 - a);
          const float out = a + below;
          if (out <= 0.0f) continue;
          for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>((colour[c] * a + p[c] * below) / out + 0.5f);
          p[3] = static_cast<uint8_t>(out * 255.0f + 0.5f);
        }
      }
    }
    penX += advance * scale;
    if (i + 1 < text.size())
      penX += scale * stbtt_GetCodepointKernAdvance(&font, cp, static_cast<unsigned char>(text[i + 1]));
  }
}

}  // namespace eng
