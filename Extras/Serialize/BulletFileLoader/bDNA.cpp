// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "bDNA.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

namespace bParse
{
namespace
{
short swapShort(short v)
{
	const unsigned short u = static_cast<unsigned short>(v);
	return static_cast<short>(static_cast<unsigned short>((u >> 8) | (u << 8)));
}

int swapInt(int v)
{
	const unsigned int u = static_cast<unsigned int>(v);
	return static_cast<int>((u >> 24) | ((u >> 8) & 0xff00u) | ((u << 8) & 0xff0000u) | (u << 24));
}

// A cursor over the block that refuses to move past its end.
struct Reader
{
	char* base;
	int size;
	int pos;
	bool ok;

	bool need(int n)
	{
		if (!ok || n < 0 || pos > size - n) ok = false;
		return ok;
	}
	bool tag(const char* name)
	{
		if (!need(4) || memcmp(base + pos, name, 4) != 0) return ok = false;
		pos += 4;
		return true;
	}
	int readInt(bool swap)
	{
		if (!need(4)) return 0;
		int v;
		memcpy(&v, base + pos, 4);
		if (swap)
		{
			v = swapInt(v);
			memcpy(base + pos, &v, 4);
		}
		pos += 4;
		return v;
	}
	short* shorts(int count, bool swap)
	{
		if (count < 0 || count > size || !need(2 * count)) return 0;
		short* first = reinterpret_cast<short*>(base + pos);
		if (swap)
			for (int i = 0; i < count; ++i)
			{
				short v;
				memcpy(&v, base + pos + 2 * i, 2);
				v = swapShort(v);
				memcpy(base + pos + 2 * i, &v, 2);
			}
		pos += 2 * count;
		return first;
	}
	char* string()
	{
		if (!ok) return 0;
		const void* end = memchr(base + pos, 0, size_t(size - pos));
		if (!end)
		{
			ok = false;
			return 0;
		}
		char* s = base + pos;
		pos = int(static_cast<const char*>(end) - base) + 1;
		return s;
	}
	void align4() { pos = (pos + 3) & ~3; }
};

// Product of the [N] suffixes; 0 for a malformed or absurd size.
int arraySizeOf(const char* name)
{
	long long count = 1;
	for (const char* c = name; *c; ++c)
	{
		if (*c != '[') continue;
		const long long n = atoll(c + 1);
		if (n <= 0 || n > (1 << 20)) return 0;
		count *= n;
		if (count > (1 << 24)) return 0;
	}
	return int(count);
}
}  // namespace

bDNA::bDNA() : mPtrLen(0) {}

bDNA::~bDNA() {}

void bDNA::clear()
{
	mNames.clear();
	mArraySizes.clear();
	mTypes.clear();
	mStructs.clear();
	mTlens.clear();
	mCMPFlags.clear();
	mStructReverse.clear();
	mTypeLookup.clear();
	mPtrLen = 0;
}

void bDNA::init(char* data, int len, bool swap)
{
	clear();
	if (!data || len <= 0) return;
	mBlock.resize(len);
	memcpy(&mBlock[0], data, size_t(len));
	Reader r = {&mBlock[0], len, 0, true};
	if (!r.tag("SDNA") || !r.tag("NAME")) return clear();
	const int nameCount = r.readInt(swap);
	if (nameCount < 0 || nameCount > len) return clear();
	for (int i = 0; i < nameCount && r.ok; ++i)
	{
		char* name = r.string();
		if (!name) break;
		mNames.push_back(name);
		mArraySizes.push_back(arraySizeOf(name));
	}
	r.align4();
	if (!r.tag("TYPE")) return clear();
	const int typeCount = r.readInt(swap);
	if (typeCount < 0 || typeCount > len || typeCount > 32767) return clear();
	for (int i = 0; i < typeCount && r.ok; ++i)
	{
		char* type = r.string();
		if (!type) break;
		mTypes.push_back(type);
	}
	r.align4();
	if (!r.tag("TLEN")) return clear();
	short* lengths = r.shorts(typeCount, swap);
	if (!lengths) return clear();
	for (int i = 0; i < typeCount; ++i)
	{
		short v;
		memcpy(&v, lengths + i, 2);
		mTlens.push_back(v);
	}
	r.align4();
	if (!r.tag("STRC")) return clear();
	const int structCount = r.readInt(swap);
	if (structCount < 0 || structCount > len) return clear();
	for (int i = 0; i < structCount && r.ok; ++i)
	{
		short* head = r.shorts(2, swap);
		if (!head) break;
		if (head[0] < 0 || head[0] >= typeCount || head[1] < 0) return clear();
		short* fields = r.shorts(2 * head[1], swap);
		if (!fields) break;
		for (int f = 0; f < head[1]; ++f)
			if (fields[2 * f] < 0 || fields[2 * f] >= typeCount || fields[2 * f + 1] < 0 ||
			    fields[2 * f + 1] >= nameCount || mArraySizes[fields[2 * f + 1]] == 0)
				return clear();
		mStructs.push_back(head);
	}
	if (!r.ok || mNames.size() != nameCount || mTypes.size() != typeCount) return clear();
	for (int i = 0; i < mStructs.size(); ++i)
	{
		const short type = mStructs[i][0];
		if (mStructReverse.find(btHashInt(type))) return clear();  // one struct per type
		mStructReverse.insert(btHashInt(type), i);
		mTypeLookup.insert(btHashString(mTypes[type]), i);
		if (!mPtrLen && strcmp(mTypes[type], "ListBase") == 0) mPtrLen = mTlens[type] / 2;
	}
}

int bDNA::getArraySize(char* str) { return str ? arraySizeOf(str) : 0; }

int bDNA::getElementSize(short type, short name)
{
	char* n = getName(name);
	if (!n || type < 0 || type >= mTlens.size()) return 0;
	const bool pointer = n[0] == '*' || (n[0] == '(' && n[1] == '*');
	return (pointer ? mPtrLen : mTlens[type]) * getArraySizeNew(name);
}

char* bDNA::getName(int ind) { return (ind >= 0 && ind < mNames.size()) ? mNames[ind] : 0; }

char* bDNA::getType(int ind) { return (ind >= 0 && ind < mTypes.size()) ? mTypes[ind] : 0; }

short* bDNA::getStruct(int ind) { return (ind >= 0 && ind < mStructs.size()) ? mStructs[ind] : 0; }

short bDNA::getLength(int ind) { return (ind >= 0 && ind < mTlens.size()) ? mTlens[ind] : short(0); }

int bDNA::getReverseType(short type)
{
	const int* found = mStructReverse.find(btHashInt(type));
	return found ? *found : -1;
}

int bDNA::getReverseType(const char* type)
{
	if (!type) return -1;
	const int* found = mTypeLookup.find(btHashString(type));
	return found ? *found : -1;
}

int bDNA::getNumStructs() { return mStructs.size(); }

bool bDNA::lessThan(bDNA* other) { return other && mStructs.size() < other->mStructs.size(); }

void bDNA::initCmpFlags(bDNA* memDNA)
{
	mCMPFlags.resize(mStructs.size());
	for (int i = 0; i < mStructs.size(); ++i)
	{
		short* old = mStructs[i];
		const int memIndex = memDNA ? memDNA->getReverseType(mTypes[old[0]]) : -1;
		if (memIndex < 0)
		{
			mCMPFlags[i] = FDF_NONE;
			continue;
		}
		short* cur = memDNA->mStructs[memIndex];
		bool equal = old[1] == cur[1] && mTlens[old[0]] == memDNA->mTlens[cur[0]];
		for (int f = 0; equal && f < old[1]; ++f)
			equal = strcmp(mTypes[old[2 + 2 * f]], memDNA->mTypes[cur[2 + 2 * f]]) == 0 &&
			        strcmp(mNames[old[3 + 2 * f]], memDNA->mNames[cur[3 + 2 * f]]) == 0;
		mCMPFlags[i] = equal ? FDF_STRUCT_EQU : FDF_STRUCT_NEQU;
	}
}

bool bDNA::flagNotEqual(int dna_nr)
{
	return dna_nr >= 0 && dna_nr < mCMPFlags.size() && mCMPFlags[dna_nr] == FDF_STRUCT_NEQU;
}

bool bDNA::flagEqual(int dna_nr)
{
	return dna_nr >= 0 && dna_nr < mCMPFlags.size() && mCMPFlags[dna_nr] == FDF_STRUCT_EQU;
}

bool bDNA::flagNone(int dna_nr) { return dna_nr >= 0 && dna_nr < mCMPFlags.size() && mCMPFlags[dna_nr] == FDF_NONE; }

int bDNA::getPointerSize() { return mPtrLen; }

void bDNA::dumpTypeDefinitions()
{
	for (int i = 0; i < mStructs.size(); ++i)
	{
		short* s = mStructs[i];
		printf("struct %s (%d bytes)\n", mTypes[s[0]], mTlens[s[0]]);
		for (int f = 0; f < s[1]; ++f) printf("\t%s %s\n", mTypes[s[2 + 2 * f]], mNames[s[3 + 2 * f]]);
	}
}
}  // namespace bParse
