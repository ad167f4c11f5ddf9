// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BULLET_FILE_H
#define BT_BULLET_FILE_H

#include "bFile.h"
#include "LinearMath/btAlignedObjectArray.h"

/// A .bullet file read into the reader's own structs, sorted by kind of chunk.

namespace bParse
{
/// A .bullet file: after parse(), each array holds the converted structs of one chunk kind (the
/// struct type of each is in its chunk's DNA name: float or double variants).
class btBulletFile : public bFile
{
protected:
	/// The reader's DNA (a copy of btDefaultSerializer's).
	char* m_DnaCopy;

public:
	btAlignedObjectArray<bStructHandle*> m_multiBodies;
	btAlignedObjectArray<bStructHandle*> m_multiBodyLinkColliders;
	btAlignedObjectArray<bStructHandle*> m_softBodies;
	btAlignedObjectArray<bStructHandle*> m_rigidBodies;
	btAlignedObjectArray<bStructHandle*> m_collisionObjects;
	btAlignedObjectArray<bStructHandle*> m_collisionShapes;
	btAlignedObjectArray<bStructHandle*> m_constraints;
	btAlignedObjectArray<bStructHandle*> m_bvhs;
	btAlignedObjectArray<bStructHandle*> m_triangleInfoMaps;
	btAlignedObjectArray<bStructHandle*> m_dynamicsWorldInfo;
	btAlignedObjectArray<bStructHandle*> m_contactManifolds;
	/// Every converted chunk, in file order.
	btAlignedObjectArray<char*> m_dataBlocks;

	/// An empty file object (reads nothing; ok() is false).
	btBulletFile();
	/// Reads fileName.
	btBulletFile(const char* fileName);
	/// Reads len bytes at memoryBuffer (not copied).
	btBulletFile(char* memoryBuffer, int len);
	~btBulletFile() override;

	void addDataBlock(char* dataBlock) override;
	/// Writes the bytes read to fileName; returns 0 on success, -1 when it cannot.
	int write(const char* fileName, bool fixupPointers = false) override;
	/// Checks the header, converts every chunk, sorts them into the arrays.
	void parse(int verboseMode) override;
	/// Sorts the converted chunks into the arrays (parse calls it).
	virtual void parseData();
};
}  // namespace bParse

#endif
