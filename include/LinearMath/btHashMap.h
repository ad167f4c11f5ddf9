// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_HASH_MAP_H
#define BT_HASH_MAP_H

/// btHashMap: a hash map whose keys and values live in dense arrays (index 0..size()-1), with
/// collision chains stored as next-indices beside them, so iteration is a plain array walk and no
/// node is ever allocated on its own. Key types provide getHash() and equals(); btHashInt,
/// btHashString, btHashPtr, btHashKey and btHashKeyPtr are the ready-made ones.
///
/// Removing an entry moves the last entry into its index, so indices of other entries may change.
/// getAtIndex and getKeyAtIndex assert on a bad index; in release builds getAtIndex returns null and
/// getKeyAtIndex is unchecked (like operator[] of btAlignedObjectArray).

#include "LinearMath/btAlignedObjectArray.h"

#include <stdint.h>
#include <string.h>

#include <string>
#include <utility>

namespace caliber
{
/// Mixes the bits of a 32-bit value so that nearby inputs land far apart (an xorshift-multiply finaliser).
SIMD_FORCE_INLINE unsigned int hashMix32(unsigned int value)
{
	value ^= value >> 16;
	value *= 0x7feb352du;
	value ^= value >> 15;
	value *= 0x846ca68bu;
	value ^= value >> 16;
	return value;
}

/// btHashMap's bucket of a key hash in a table of bucketCount buckets (a power of two >= 2): the hash
/// is re-mixed (Fibonacci hashing, the top bits) so that user key types with weak hashes still spread.
SIMD_FORCE_INLINE int hashMapBucket(unsigned int hash, int bucketCount)
{
#if defined(__GNUC__)
	const int bits = __builtin_ctz(unsigned(bucketCount));
#else
	int bits = 0;
	while ((1 << bits) < bucketCount) ++bits;
#endif
	return int((hash * 2654435769u) >> (32 - bits));
}

/// Makes the link (the bucket's head or an entry's next index) that points at entry index point at
/// replacement instead; the entry must be in that bucket's chain.
inline void hashMapRelink(int* bucketHead, int* next, int index, int replacement)
{
	int* link = bucketHead;
	while (*link != index)
	{
		btAssert(*link >= 0);
		link = &next[*link];
	}
	*link = replacement;
}
}  // namespace caliber

/// Key wrapping a copied string (the map keeps its own copy, so the caller's buffer may go away).
struct btHashString
{
	/// The key text.
	std::string m_string1;
	/// Hash of m_string1, computed once at construction.
	unsigned int m_hash;

	/// Copies name (null is treated as ""), and hashes it with 32-bit FNV-1a.
	btHashString(const char* name) : m_string1(name ? name : ""), m_hash(2166136261u)
	{
		for (unsigned char c : m_string1)
		{
			m_hash ^= c;
			m_hash *= 16777619u;
		}
	}

	/// The hash value used by btHashMap.
	unsigned int getHash() const { return m_hash; }

	/// strcmp-like comparison: negative, zero or positive as src sorts before, equal to or after dst.
	int portableStringCompare(const char* src, const char* dst) const { return strcmp(src, dst); }

	/// True when both keys hold the same text.
	bool equals(const btHashString& other) const { return m_hash == other.m_hash && m_string1 == other.m_string1; }
};

/// Key wrapping an int.
class btHashInt
{
	int m_uid;

public:
	/// Default key (0), so that keys can be stored in arrays.
	btHashInt() : m_uid(0) {}
	/// Key for uid.
	btHashInt(int uid) : m_uid(uid) {}

	/// The wrapped int.
	int getUid1() const { return m_uid; }
	/// Replaces the wrapped int.
	void setUid1(int uid) { m_uid = uid; }

	/// True when both keys wrap the same int.
	bool equals(const btHashInt& other) const { return m_uid == other.m_uid; }
	/// The hash value used by btHashMap.
	unsigned int getHash() const { return caliber::hashMix32(static_cast<unsigned int>(m_uid)); }
};

/// Key wrapping a pointer (compared by address, never dereferenced).
class btHashPtr
{
	const void* m_pointer;

public:
	/// Key for ptr.
	btHashPtr(const void* ptr) : m_pointer(ptr) {}

	/// The wrapped pointer.
	const void* getPointer() const { return m_pointer; }

	/// True when both keys wrap the same address.
	bool equals(const btHashPtr& other) const { return m_pointer == other.m_pointer; }

	/// The hash value used by btHashMap (both halves of a 64-bit address contribute).
	unsigned int getHash() const
	{
		const uint64_t bits = static_cast<uint64_t>(reinterpret_cast<uintptr_t>(m_pointer));
		return caliber::hashMix32(static_cast<unsigned int>(bits) ^
		                          caliber::hashMix32(static_cast<unsigned int>(bits >> 32)));
	}
};

/// Int key typed by the value it maps to (keeps keys for different maps apart at compile time).
template <class Value>
class btHashKeyPtr
{
	int m_uid;

public:
	/// Key for uid.
	btHashKeyPtr(int uid) : m_uid(uid) {}

	/// The wrapped int.
	int getUid1() const { return m_uid; }

	/// True when both keys wrap the same int.
	bool equals(const btHashKeyPtr<Value>& other) const { return getUid1() == other.getUid1(); }

	/// The hash value used by btHashMap.
	unsigned int getHash() const { return caliber::hashMix32(static_cast<unsigned int>(m_uid)); }
};

/// Int key typed by the value it maps to.
template <class Value>
class btHashKey
{
	int m_uid;

public:
	/// Key for uid.
	btHashKey(int uid) : m_uid(uid) {}

	/// The wrapped int.
	int getUid1() const { return m_uid; }

	/// True when both keys wrap the same int.
	bool equals(const btHashKey<Value>& other) const { return getUid1() == other.getUid1(); }

	/// The hash value used by btHashMap.
	unsigned int getHash() const { return caliber::hashMix32(static_cast<unsigned int>(m_uid)); }
};

/// Hash map from Key (with getHash() and equals()) to Value, stored in dense arrays.
template <class Key, class Value>
class btHashMap
{
protected:
	/// First entry index of each bucket, or -1; the bucket count is a power of two (or 0 before the first insert).
	btAlignedObjectArray<int> m_hashTable;
	/// Next entry index in the same bucket, or -1; parallel to m_keyArray.
	btAlignedObjectArray<int> m_next;
	/// Values, in entry order.
	btAlignedObjectArray<Value> m_valueArray;
	/// Keys, in entry order.
	btAlignedObjectArray<Key> m_keyArray;

	/// Makes the bucket table big enough for the entries (load factor at most 1: the table doubles,
	/// starting at 16 buckets) and relinks every entry; insert calls it after adding an entry. The key
	/// is not used (Bullet's signature).
	void growTables(const Key& /*key*/)
	{
		int bucketCount = m_hashTable.size() > 0 ? m_hashTable.size() : 16;
		while (bucketCount < m_keyArray.size()) bucketCount *= 2;
		if (bucketCount == m_hashTable.size()) return;
		m_hashTable.resize(bucketCount);
		for (int b = 0; b < bucketCount; ++b) m_hashTable[b] = -1;
		for (int i = 0; i < m_keyArray.size(); ++i)
		{
			const int bucket = caliber::hashMapBucket(m_keyArray[i].getHash(), bucketCount);
			m_next[i] = m_hashTable[bucket];
			m_hashTable[bucket] = i;
		}
	}

public:
	/// Adds key with value, or replaces the value when key is present.
	void insert(const Key& key, const Value& value)
	{
		const int existing = findIndex(key);
		if (existing >= 0)
		{
			m_valueArray[existing] = value;
			return;
		}
		const int index = m_keyArray.size();
		m_keyArray.push_back(key);
		m_valueArray.push_back(value);
		m_next.push_back(-1);
		// Load factor at most 1: chains stay short and the table doubles with the entries.
		if (index + 1 > m_hashTable.size())
		{
			growTables(key);
			return;
		}
		const int bucket = caliber::hashMapBucket(key.getHash(), m_hashTable.size());
		m_next[index] = m_hashTable[bucket];
		m_hashTable[bucket] = index;
	}

	/// Removes key if present; the last entry moves into the freed index, every other key stays findable.
	void remove(const Key& key)
	{
		const int index = findIndex(key);
		if (index < 0) return;
		const int buckets = m_hashTable.size();
		caliber::hashMapRelink(&m_hashTable[caliber::hashMapBucket(m_keyArray[index].getHash(), buckets)], &m_next[0],
		                       index, m_next[index]);
		const int last = m_keyArray.size() - 1;
		if (index != last)
		{
			// Move the last entry into the hole and repoint whichever link referred to it.
			caliber::hashMapRelink(&m_hashTable[caliber::hashMapBucket(m_keyArray[last].getHash(), buckets)],
			                       &m_next[0], last, index);
			m_keyArray[index] = std::move(m_keyArray[last]);
			m_valueArray[index] = std::move(m_valueArray[last]);
			m_next[index] = m_next[last];
		}
		m_keyArray.pop_back();
		m_valueArray.pop_back();
		m_next.pop_back();
	}

	/// Number of entries.
	int size() const { return m_keyArray.size(); }

	/// Value of entry index (0..size()-1); asserts on a bad index, null in release.
	const Value* getAtIndex(int index) const
	{
		btAssert(index >= 0 && index < m_valueArray.size());
		if (index < 0 || index >= m_valueArray.size()) return nullptr;
		return &m_valueArray[index];
	}

	/// Value of entry index (0..size()-1); asserts on a bad index, null in release.
	Value* getAtIndex(int index)
	{
		btAssert(index >= 0 && index < m_valueArray.size());
		if (index < 0 || index >= m_valueArray.size()) return nullptr;
		return &m_valueArray[index];
	}

	/// Key of entry index (0..size()-1); asserts on a bad index, unchecked in release (keys need not
	/// be default-constructible, so there is no "empty" key to return).
	Key getKeyAtIndex(int index) { return m_keyArray[index]; }

	/// Key of entry index (0..size()-1); asserts on a bad index, unchecked in release.
	const Key getKeyAtIndex(int index) const { return m_keyArray[index]; }

	/// Value for key, or null when absent.
	Value* operator[](const Key& key) { return find(key); }

	/// Value for key, or null when absent.
	const Value* operator[](const Key& key) const { return find(key); }

	/// Value for key, or null when absent.
	const Value* find(const Key& key) const
	{
		const int index = findIndex(key);
		return index >= 0 ? &m_valueArray[index] : nullptr;
	}

	/// Value for key, or null when absent.
	Value* find(const Key& key)
	{
		const int index = findIndex(key);
		return index >= 0 ? &m_valueArray[index] : nullptr;
	}

	/// Entry index of key, or -1 when absent.
	int findIndex(const Key& key) const
	{
		if (m_hashTable.size() == 0) return -1;
		for (int i = m_hashTable[caliber::hashMapBucket(key.getHash(), m_hashTable.size())]; i >= 0; i = m_next[i])
			if (key.equals(m_keyArray[i])) return i;
		return -1;
	}

	/// Removes every entry and frees the storage.
	void clear()
	{
		m_hashTable.clear();
		m_next.clear();
		m_valueArray.clear();
		m_keyArray.clear();
	}
};

#endif  // BT_HASH_MAP_H
