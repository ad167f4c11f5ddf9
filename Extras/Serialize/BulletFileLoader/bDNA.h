// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef __BDNA_H__
#define __BDNA_H__

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btHashMap.h"

/// The DNA of a .bullet file: the names, types, type lengths and structs that describe its chunks.

namespace bParse
{
/// A parsed SDNA block. init() checks every count, index and string against the block's size; a
/// block that fails leaves the DNA empty (getNumStructs() == 0, getPointerSize() == 0).
class bDNA
{
public:
	bDNA();
	~bDNA();

	/// Parses an SDNA block of len bytes (swap: the block has the other byte order). The block is
	/// copied, so data may go away afterwards.
	void init(char* data, int len, bool swap = false);

	/// Product of the [N] suffixes of a field name.
	int getArraySize(char* str);
	/// Product of the [N] suffixes of name index name.
	int getArraySizeNew(short name) { return (name >= 0 && name < mArraySizes.size()) ? mArraySizes[name] : 0; }
	/// Bytes of a field of type type and name name (pointer size for pointers, times the array size).
	int getElementSize(short type, short name);

	/// Field or struct name number ind (0 when out of range).
	char* getName(int ind);
	/// Type name number ind (0 when out of range).
	char* getType(int ind);
	/// Struct ind: type, field count, then (type, name) pairs (0 when out of range).
	short* getStruct(int ind);
	/// Byte length of type ind (0 when out of range).
	short getLength(int ind);
	/// The struct index of type index type, or -1.
	int getReverseType(short type);
	/// The struct index of the type named type, or -1.
	int getReverseType(const char* type);
	/// Number of structs (0 when init failed).
	int getNumStructs();
	/// Number of names.
	int getNumNames() const { return mNames.size(); }
	/// Number of types.
	int getNumTypes() const { return mTypes.size(); }
	/// True when this DNA has fewer structs than other.
	bool lessThan(bDNA* other);
	/// Marks each struct as equal to, different from or missing in memDNA.
	void initCmpFlags(bDNA* memDNA);
	/// True when struct dna_nr differs from the memory DNA's struct of the same name.
	bool flagNotEqual(int dna_nr);
	/// True when struct dna_nr equals the memory DNA's struct of the same name.
	bool flagEqual(int dna_nr);
	/// True when the memory DNA has no struct of that name.
	bool flagNone(int dna_nr);
	/// The pointer size the DNA was written with (from its ListBase struct), or 0.
	int getPointerSize();
	/// Prints every struct with its fields.
	void dumpTypeDefinitions();

private:
	enum FileDNAFlags
	{
		FDF_NONE = 0,
		FDF_STRUCT_NEQU,
		FDF_STRUCT_EQU
	};
	void clear();

	btAlignedObjectArray<char> mBlock;
	btAlignedObjectArray<int> mCMPFlags;
	btAlignedObjectArray<char*> mNames;
	btAlignedObjectArray<int> mArraySizes;
	btAlignedObjectArray<char*> mTypes;
	btAlignedObjectArray<short*> mStructs;
	btAlignedObjectArray<short> mTlens;
	btHashMap<btHashInt, int> mStructReverse;
	btHashMap<btHashString, int> mTypeLookup;
	int mPtrLen;
};
}  // namespace bParse

#endif
