// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WORLD_SNAPSHOT_STREAM_H
#define CALIBER_WORLD_SNAPSHOT_STREAM_H

// The byte stream of a world snapshot: native byte order and precision (the header records both), each
// field written as its raw bytes, vectors as x, y, z (the unused fourth lane is not state). The writer
// can log every field (offset, part, index, name), which is how compareWorldState names the first
// difference. The reader checks every length and can run dry (reading without writing anything back),
// which is how restoreWorldState validates a whole buffer before it touches the world.

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// One logged field of a written snapshot.
struct SnapshotField
{
	size_t offset;
	size_t size;
	const char* section;
	int index;
	const char* name;
	int subIndex;  ///< a manifold point or a warm-start row, -1 otherwise
};

class SnapshotWriter
{
public:
	SnapshotWriter(btAlignedObjectArray<unsigned char>& out, btAlignedObjectArray<SnapshotField>* log)
	    : m_out(out), m_log(log)
	{
	}
	/// The part and index the following fields belong to (for the log).
	void context(const char* section, int index, int subIndex = -1)
	{
		m_section = section;
		m_index = index;
		m_subIndex = subIndex;
	}
	void bytes(const char* name, const void* data, size_t size)
	{
		if (m_log)
		{
			SnapshotField field = {size_t(m_out.size()), size, m_section, m_index, name, m_subIndex};
			m_log->push_back(field);
		}
		const int at = m_out.size();
		// btAlignedObjectArray::resize reserves exactly what it is asked for: grow geometrically here.
		if (at + int(size) > m_out.capacity()) m_out.reserve(btMax(at + int(size), 2 * m_out.capacity()));
		m_out.resize(at + int(size));
		if (size) memcpy(&m_out[at], data, size);
	}
	template <class T>
	void field(const char* name, const T& value)
	{
		bytes(name, &value, sizeof(T));
	}
	void field(const char* name, const bool& value)
	{
		const unsigned char byte = value ? 1 : 0;
		bytes(name, &byte, 1);
	}
	void field(const char* name, const btVector3& value) { bytes(name, value.m_floats, 3 * sizeof(btScalar)); }
	void field(const char* name, const btQuaternion& value)
	{
		const btScalar q[4] = {value.x(), value.y(), value.z(), value.w()};
		bytes(name, q, sizeof(q));
	}
	/// The checked fields of the reader, written as plain fields.
	void field(const char* name, const int& value, int, int) { field(name, value); }
	void fieldKeepingBits(const char* name, const int& value, int) { field(name, value); }
	void field(const char* name, const btMatrix3x3& value)
	{
		btScalar rows[9];
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) rows[3 * r + c] = value[r][c];
		bytes(name, rows, sizeof(rows));
	}
	void field(const char* name, const btTransform& value)
	{
		field(name, value.getBasis());
		field(name, value.getOrigin());
	}

private:
	btAlignedObjectArray<unsigned char>& m_out;
	btAlignedObjectArray<SnapshotField>* m_log;
	const char* m_section = "header";
	int m_index = -1;
	int m_subIndex = -1;
};

class SnapshotReader
{
public:
	/// apply false: a dry run that reads and checks but writes nothing back through field().
	SnapshotReader(const unsigned char* data, size_t size, bool apply) : m_data(data), m_size(size), m_apply(apply) {}

	bool ok() const { return !m_failed; }
	bool applying() const { return m_apply; }
	const char* error() const { return m_error; }
	size_t remaining() const { return m_size - m_pos; }

	/// Records the first failure (later ones keep the first message).
	void fail(const char* format, ...)
	{
		if (m_failed) return;
		m_failed = true;
		va_list args;
		va_start(args, format);
		vsnprintf(m_error, sizeof(m_error), format, args);
		va_end(args);
	}
	bool bytes(const char* name, void* data, size_t size)
	{
		if (m_failed) return false;
		if (size > m_size - m_pos)
		{
			fail("truncated: %s at byte %zu needs %zu bytes, %zu left", name, m_pos, size, m_size - m_pos);
			return false;
		}
		memcpy(data, m_data + m_pos, size);
		m_pos += size;
		return true;
	}
	/// Reads a value that is always returned (counts, indices, kinds).
	template <class T>
	T value(const char* name)
	{
		T v = T();
		bytes(name, &v, sizeof(T));
		return v;
	}
	/// Reads a bool that is always returned.
	bool flag(const char* name)
	{
		unsigned char byte = 0;
		if (bytes(name, &byte, 1) && byte > 1) fail("%s: %u is not a bool", name, unsigned(byte));
		return byte == 1;
	}
	/// Reads a finite scalar that is always returned.
	btScalar scalar(const char* name)
	{
		btScalar v = 0;
		if (bytes(name, &v, sizeof(v))) checkFinite(name, &v, 1);
		return ok() ? v : btScalar(0);
	}
	/// Reads a finite vector (x, y, z) that is always returned.
	btVector3 vector(const char* name)
	{
		btScalar xyz[3] = {0, 0, 0};
		if (bytes(name, xyz, sizeof(xyz))) checkFinite(name, xyz, 3);
		return ok() ? btVector3(xyz[0], xyz[1], xyz[2]) : btVector3(0, 0, 0);
	}
	/// Reads an int in [min, max] and writes it to target when applying.
	void field(const char* name, int& target, int min, int max)
	{
		const int v = value<int>(name);
		if (ok() && (v < min || v > max)) fail("%s: %d is outside [%d, %d]", name, v, min, max);
		if (ok() && m_apply) target = v;
	}
	/// Reads an int whose mask bits must equal target's (bits that would change what an object is).
	void fieldKeepingBits(const char* name, int& target, int mask)
	{
		const int v = value<int>(name);
		if (ok() && (v & mask) != (target & mask)) fail("%s: 0x%x changes bits 0x%x of 0x%x", name, v, mask, target);
		if (ok() && m_apply) target = v;
	}
	/// Reads a count in [0, limit]; a bad count fails the reader and gives 0.
	int count(const char* name, int limit)
	{
		const int n = value<int>(name);
		if (!ok()) return 0;
		if (n < 0 || n > limit)
		{
			fail("%s: %d is outside [0, %d]", name, n, limit);
			return 0;
		}
		return n;
	}
	/// Reads a value and writes it to target when applying.
	template <class T>
	void field(const char* name, T& target)
	{
		T v;
		if (bytes(name, &v, sizeof(T)) && m_apply) target = v;
	}
	void field(const char* name, bool& target)
	{
		unsigned char byte = 0;
		if (!bytes(name, &byte, 1)) return;
		if (byte > 1) fail("%s: %u is not a bool", name, unsigned(byte));
		if (m_apply) target = byte != 0;
	}
	void field(const char* name, btScalar& target)
	{
		const btScalar v = scalar(name);
		if (ok() && m_apply) target = v;
	}
	void field(const char* name, btVector3& target)
	{
		const btVector3 v = vector(name);
		if (ok() && m_apply) target = v;
	}
	void field(const char* name, btMatrix3x3& target)
	{
		btScalar m[9];
		if (bytes(name, m, sizeof(m)) && checkFinite(name, m, 9) && m_apply)
			target.setValue(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8]);
	}
	void field(const char* name, btQuaternion& target)
	{
		btScalar q[4];
		if (!bytes(name, q, sizeof(q)) || !checkFinite(name, q, 4)) return;
		if (m_apply) target.setValue(q[0], q[1], q[2], q[3]);
	}
	void field(const char* name, btTransform& target)
	{
		btScalar m[12];
		if (!bytes(name, m, sizeof(m)) || !checkFinite(name, m, 12)) return;
		// A pose's basis is a rotation: rows of unit length, at right angles (a bit-flipped value is not).
		for (int r = 0; r < 3; ++r)
			for (int c = r; c < 3; ++c)
			{
				const btScalar dot = m[3 * r] * m[3 * c] + m[3 * r + 1] * m[3 * c + 1] + m[3 * r + 2] * m[3 * c + 2];
				if (btFabs(dot - (r == c ? btScalar(1) : btScalar(0))) > btScalar(1e-3))
				{
					fail("%s: the basis is not a rotation", name);
					return;
				}
			}
		if (m_apply)
		{
			target.getBasis().setValue(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8]);
			target.getOrigin().setValue(m[9], m[10], m[11]);
		}
	}

private:
	bool checkFinite(const char* name, const btScalar* values, int count)
	{
		for (int i = 0; i < count; ++i)
		{
			if (!(values[i] == values[i]) || btFabs(values[i]) > BT_LARGE_FLOAT * BT_LARGE_FLOAT)
			{
				fail("%s: not a finite number", name);
				return false;
			}
		}
		return true;
	}

	const unsigned char* m_data;
	size_t m_size;
	size_t m_pos = 0;
	bool m_apply;
	bool m_failed = false;
	char m_error[256] = {0};
};
}  // namespace caliber

#endif  // CALIBER_WORLD_SNAPSHOT_STREAM_H
