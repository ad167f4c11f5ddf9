// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GEN_LIST_H
#define BT_GEN_LIST_H

/// Bullet's small intrusive doubly linked list: an object derives from btGEN_Link and is linked into a
/// btGEN_List, which owns two sentinel links (head and tail) so that insertion and removal never test
/// for the ends. Not thread-safe; a link must be in at most one list.
class btGEN_Link
{
public:
	btGEN_Link() : m_next(0), m_prev(0) {}
	btGEN_Link(btGEN_Link* next, btGEN_Link* prev) : m_next(next), m_prev(prev) {}

	btGEN_Link* getNext() const { return m_next; }
	btGEN_Link* getPrev() const { return m_prev; }

	/// True for the sentinels: the head has no previous link, the tail no next one.
	bool isHead() const { return m_prev == 0; }
	bool isTail() const { return m_next == 0; }

	/// Links this just before `link` (which must be in a list).
	void insertBefore(btGEN_Link* link)
	{
		m_next = link;
		m_prev = link->m_prev;
		m_next->m_prev = this;
		m_prev->m_next = this;
	}

	/// Links this just after `link` (which must be in a list).
	void insertAfter(btGEN_Link* link)
	{
		m_next = link->m_next;
		m_prev = link;
		m_next->m_prev = this;
		m_prev->m_next = this;
	}

	/// Unlinks this from its list (it must be in one).
	void remove()
	{
		m_next->m_prev = m_prev;
		m_prev->m_next = m_next;
	}

private:
	btGEN_Link* m_next;
	btGEN_Link* m_prev;
};

class btGEN_List
{
public:
	btGEN_List() : m_head(&m_tail, 0), m_tail(0, &m_head) {}
	btGEN_List(const btGEN_List&) = delete;
	btGEN_List& operator=(const btGEN_List&) = delete;

	/// The first link, or the tail sentinel when the list is empty.
	btGEN_Link* getHead() const { return m_head.getNext(); }
	/// The last link, or the head sentinel when the list is empty.
	btGEN_Link* getTail() const { return m_tail.getPrev(); }

	void addHead(btGEN_Link* link) { link->insertAfter(&m_head); }
	void addTail(btGEN_Link* link) { link->insertBefore(&m_tail); }

private:
	btGEN_Link m_head;
	btGEN_Link m_tail;
};

#endif  // BT_GEN_LIST_H
