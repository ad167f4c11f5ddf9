// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_BITMAP_FONT_H
#define CALIBER_DEMOS_COMMON_BITMAP_FONT_H
// A tiny built-in 5 x 7 pixel font of our own (capitals, digits and the punctuation numbers and
// profiles need; lower case is drawn in capitals), laid out as filled cells that any renderer can draw
// as quads: the demo browser's on-screen text. Demo-side code.

#include <string>
#include <vector>

namespace caliber
{
namespace demo
{
/// Glyph size in font pixels, and the advance from one character to the next (one blank column).
const int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6, kLineAdvance = 9;

/// The rows of c's glyph, top first, bit 4 the leftmost column. A character the font lacks is drawn
/// as a hollow box (so that a missing glyph shows, rather than vanishing); a space is blank.
const unsigned char* glyphRows(char c);

/// One lit font pixel: its top-left corner in screen pixels (y down) and its size.
struct TextCell
{
	float x, y, size;
};

/// Appends the cells of text written from (x, y) (the top-left of its first glyph) with font pixels
/// of `scale` screen pixels; '\n' starts a new line. Returns the width of the widest line in screen
/// pixels. A scale that is not positive and finite writes nothing.
float layoutText(const std::string& text, float x, float y, float scale, std::vector<TextCell>& cells);
}  // namespace demo
}  // namespace caliber

#endif
