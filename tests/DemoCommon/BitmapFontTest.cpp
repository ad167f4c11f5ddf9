// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The demo browser's bitmap font (Demos/Common/BitmapFont): glyphs that tell characters apart, text
// laid out where and as wide as the font's metrics say, and what it does with input it cannot draw.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>

#include "BitmapFont.h"

using namespace caliber::demo;

namespace
{
int litCells(char c)
{
	const unsigned char* rows = glyphRows(c);
	int n = 0;
	for (int r = 0; r < kGlyphHeight; ++r)
		for (int col = 0; col < kGlyphWidth; ++col) n += (rows[r] >> col) & 1;
	return n;
}
std::string rowsOf(char c) { return std::string(reinterpret_cast<const char*>(glyphRows(c)), kGlyphHeight); }
}  // namespace

// Readable text needs every capital, digit and printed punctuation mark to look different from every
// other, and from the box that marks a missing glyph; only the space is blank.
TEST(DemoBitmapFont, EveryPrintableCharacterHasItsOwnGlyph)
{
	const std::string box = rowsOf(char(1));
	std::set<std::string> seen;
	for (char c = '!'; c <= '~'; ++c)
	{
		if (c >= 'a' && c <= 'z') continue;  // drawn as capitals
		SCOPED_TRACE(std::string(1, c));
		EXPECT_GT(litCells(c), 0);
		EXPECT_NE(rowsOf(c), box);
		EXPECT_TRUE(seen.insert(rowsOf(c)).second) << "two characters share a glyph";
		for (int r = 0; r < kGlyphHeight; ++r) EXPECT_EQ(glyphRows(c)[r] & ~0x1f, 0);  // five columns only
	}
	EXPECT_EQ(litCells(' '), 0);
	EXPECT_EQ(rowsOf('q'), rowsOf('Q'));
}

// Layout: one cell per lit font pixel, each `scale` wide, inside the text's box; "10" at scale 2 is
// two glyphs of 5 columns with one blank column between: (5 + 1 + 5) x 2 = 22 pixels wide.
TEST(DemoBitmapFont, TextCellsFillTheBoxTheMetricsGive)
{
	std::vector<TextCell> cells;
	const float width = layoutText("10", 3, 4, 2, cells);
	EXPECT_FLOAT_EQ(width, 22);
	EXPECT_EQ(int(cells.size()), litCells('1') + litCells('0'));
	for (const TextCell& cell : cells)
	{
		EXPECT_FLOAT_EQ(cell.size, 2);
		EXPECT_GE(cell.x, 3);
		EXPECT_LE(cell.x + cell.size, 3 + width);
		EXPECT_GE(cell.y, 4);
		EXPECT_LE(cell.y + cell.size, 4 + kGlyphHeight * 2);
	}
	// A new line starts back at x, kLineAdvance font pixels lower; the widest line is the width.
	cells.clear();
	EXPECT_FLOAT_EQ(layoutText("1\n100", 0, 0, 1, cells), 17);
	float lowest = 0;
	for (const TextCell& cell : cells) lowest = std::fmax(lowest, cell.y);
	EXPECT_FLOAT_EQ(lowest, float(kLineAdvance + kGlyphHeight - 1));
}

// Bad input: a scale or origin that is not positive and finite writes nothing (width 0); a character
// outside the font (control or non-ASCII bytes) is drawn as the box, not skipped or read out of range.
TEST(DemoBitmapFont, UnusableScalesWriteNothingAndUnknownCharactersShowABox)
{
	std::vector<TextCell> cells;
	EXPECT_EQ(layoutText("ABC", 0, 0, 0, cells), 0);
	EXPECT_EQ(layoutText("ABC", 0, 0, -1, cells), 0);
	EXPECT_EQ(layoutText("ABC", 0, 0, std::numeric_limits<float>::quiet_NaN(), cells), 0);
	EXPECT_EQ(layoutText("ABC", std::numeric_limits<float>::infinity(), 0, 1, cells), 0);
	EXPECT_TRUE(cells.empty());
	const std::string box = rowsOf(char(1));
	EXPECT_EQ(rowsOf(char(0xE9)), box);  // a Latin-1 byte
	EXPECT_EQ(rowsOf('\t'), box);
	EXPECT_EQ(litCells(char(1)), 20);  // the box's outline: top and bottom 5 each, 2 x 5 sides
	EXPECT_FLOAT_EQ(layoutText("\xC3\xA9", 0, 0, 1, cells), 11);  // two bytes, two boxes
}
