// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/SerializerDna.h"

#include <stdlib.h>
#include <string.h>

#include <string>
#include <vector>

namespace caliber
{
namespace
{
#include "LinearMath/SerializerDnaTables.inc"

// Byte sizes of the basic types, in the order makedna lists them first.
const short kBasicLengths[] = {1, 1, 2, 2, 4, 4, 4, 4, 8, 0};
const int kBasicCount = int(sizeof(kBasicLengths) / sizeof(kBasicLengths[0]));

// Product of the [N] suffixes of a DNA name (1 without any).
int arrayCount(const char* name)
{
	int count = 1;
	for (const char* c = name; *c; ++c)
		if (*c == '[') count *= atoi(c + 1);
	return count;
}

struct Builder
{
	std::vector<short> lengths;
	std::vector<int> structOfType;
	std::vector<const short*> structStart;

	short lengthOf(int type, int depth)
	{
		if (lengths[size_t(type)] >= 0) return lengths[size_t(type)];
		const int s = structOfType[size_t(type)];
		if (s < 0 || depth > 64) return lengths[size_t(type)] = 0;  // a type only pointed to
		const short* strc = structStart[size_t(s)];
		int total = 0;
		for (int f = 0; f < strc[1]; ++f)
		{
			const char* name = kDnaNames[strc[2 + 2 * f + 1]];
			const int elem = name[0] == '*' ? int(sizeof(void*)) : lengthOf(strc[2 + 2 * f], depth + 1);
			total += elem * arrayCount(name);
		}
		return lengths[size_t(type)] = short(total);
	}
};

void append(std::string& out, const void* data, size_t n) { out.append(static_cast<const char*>(data), n); }

void padTo4(std::string& out)
{
	while (out.size() % 4) out.push_back('\0');
}

std::string buildBlock()
{
	const int typeCount = int(sizeof(kDnaTypes) / sizeof(kDnaTypes[0]));
	const int nameCount = int(sizeof(kDnaNames) / sizeof(kDnaNames[0]));
	Builder b;
	b.lengths.assign(size_t(typeCount), -1);
	b.structOfType.assign(size_t(typeCount), -1);
	for (int i = 0; i < kBasicCount; ++i) b.lengths[size_t(i)] = kBasicLengths[i];
	const short* strc = kDnaStructs;
	for (int s = 0; s < kDnaStructCount; ++s)
	{
		b.structOfType[size_t(strc[0])] = s;
		b.structStart.push_back(strc);
		strc += 2 + 2 * strc[1];
	}
	for (int t = 0; t < typeCount; ++t) b.lengthOf(t, 0);

	std::string out;
	out += "SDNANAME";
	append(out, &nameCount, 4);
	for (int i = 0; i < nameCount; ++i) out.append(kDnaNames[i], strlen(kDnaNames[i]) + 1);
	padTo4(out);
	out += "TYPE";
	append(out, &typeCount, 4);
	for (int i = 0; i < typeCount; ++i) out.append(kDnaTypes[i], strlen(kDnaTypes[i]) + 1);
	padTo4(out);
	out += "TLEN";
	append(out, b.lengths.data(), b.lengths.size() * sizeof(short));
	padTo4(out);
	out += "STRC";
	append(out, &kDnaStructCount, 4);
	append(out, kDnaStructs, size_t(strc - kDnaStructs) * sizeof(short));
	padTo4(out);
	return out;
}
}  // namespace

const MemoryDnaBlock& memoryDna()
{
	static const std::string block = buildBlock();
	static const MemoryDnaBlock result = {block.data(), int(block.size())};
	return result;
}

void parseMemoryDna(char* block, int size, DnaView& view)
{
	(void)size;
	char* cp = block + 8;  // "SDNA" "NAME"
	int count;
	memcpy(&count, cp, 4);
	cp += 4;
	for (int i = 0; i < count; ++i) cp += strlen(cp) + 1;
	while ((cp - block) % 4) ++cp;
	cp += 4;  // "TYPE"
	memcpy(&view.typeCount, cp, 4);
	cp += 4;
	view.types.resize(size_t(view.typeCount));
	for (int i = 0; i < view.typeCount; ++i)
	{
		view.types[i] = cp;
		cp += strlen(cp) + 1;
	}
	while ((cp - block) % 4) ++cp;
	cp += 4;  // "TLEN"
	view.typeLengths = reinterpret_cast<short*>(cp);
	cp += 2 * view.typeCount;
	while ((cp - block) % 4) ++cp;
	cp += 4;  // "STRC"
	memcpy(&view.structCount, cp, 4);
	cp += 4;
	view.structs = reinterpret_cast<short*>(cp);
}
}  // namespace caliber
