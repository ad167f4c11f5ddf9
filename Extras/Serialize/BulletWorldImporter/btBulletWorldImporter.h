// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BULLET_WORLD_IMPORTER_H
#define BULLET_WORLD_IMPORTER_H

#include "btWorldImporter.h"

/// Loads .bullet files (float or double, 4- or 8-byte pointers, either byte order) into a world.

namespace bParse
{
class btBulletFile;
}

/// Reads a .bullet file and builds its shapes, bodies, joints and world settings (added to the world
/// given to the constructor, if any). Every pointer, count and index of the file is checked first: an
/// object whose data is inconsistent is skipped with a warning; a malformed file loads nothing and
/// the load returns false (docs/serialization.md).
class btBulletWorldImporter : public btWorldImporter
{
public:
	btBulletWorldImporter(btDynamicsWorld* world = 0);
	~btBulletWorldImporter() override;

	/// Loads fileName; false when the file cannot be read or is not a valid .bullet file.
	bool loadFile(const char* fileName, const char* preSwapFilenameOut = 0);
	/// Loads len bytes at memoryBuffer (used only during the call).
	bool loadFileFromMemory(char* memoryBuffer, int len);
	/// Builds the objects of a parsed file.
	bool loadFileFromMemory(bParse::btBulletFile* file);
	/// Builds every object of bulletFile; false when the file is not ok.
	virtual bool convertAllObjects(bParse::btBulletFile* bulletFile);
};

#endif
