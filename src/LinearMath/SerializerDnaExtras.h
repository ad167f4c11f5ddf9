// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SERIALIZER_DNA_EXTRAS_H
#define CALIBER_SERIALIZER_DNA_EXTRAS_H

// Structs the DNA holds that no Caliber class writes. Readers of the .bullet format take the
// pointer size from the length of ListBase (two pointers), so every DNA block describes it.

/// Two pointers: its length in the DNA gives the writer's pointer size.
struct ListBase
{
	void* first;
	void* last;
};

#endif
