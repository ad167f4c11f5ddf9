// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MEMBER_ACCESS_H
#define CALIBER_MEMBER_ACCESS_H

// Internal: reading a Bullet-declared class's protected or private members from Caliber's free
// functions in src/, so that the class needs neither friends nor accessors (it stays Bullet's facade).
//
// A pointer to a member named in the arguments of an explicit template instantiation is exempt from
// access checking ([temp.explicit]). The instantiation defines a friend function that returns it; the
// pointer is a constant, so `object.*caliber::memberOf(Tag{})` compiles to a plain member read.
//
// Use at namespace scope, in one .cpp only (the friend function is defined there), with a tag name
// unique in the library:
//   CALIBER_MEMBER_ACCESS(SixDofLinearRowAxis, btGeneric6DofConstraint, btVector3[3], m_linearRowAxis)
//   ... joint.*caliber::memberOf(caliber::SixDofLinearRowAxis{}) ...
// A renamed or removed member fails to compile here, not silently.

namespace caliber
{
template <class Class, class Member>
using MemberPointer = Member Class::*;

template <class Tag, typename Tag::Type Member>
struct MemberBinding
{
	friend constexpr typename Tag::Type memberOf(Tag) { return Member; }
};
}  // namespace caliber

// The tag lives in namespace caliber, where MemberBinding defines its friend.
#define CALIBER_MEMBER_ACCESS(Tag, Class, MemberType, member) \
	namespace caliber                                         \
	{                                                         \
	struct Tag                                                \
	{                                                         \
		using Type = MemberPointer<Class, MemberType>;        \
		friend constexpr Type memberOf(Tag);                  \
	};                                                        \
	template struct MemberBinding<Tag, &Class::member>;       \
	}

#endif  // CALIBER_MEMBER_ACCESS_H
