// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::angularMotionDisc (btAngularMotionDisc.h) works the disc out inline for a plain btBoxShape; it
// must give the virtual getAngularMotionDisc's value bit for bit, and leave every other shape to it.

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "BulletCollision/CollisionShapes/btAngularMotionDisc.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"

namespace
{
bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }

// A box whose bounding sphere is its own: the inline path must not be taken for it.
struct FatBox : public btBoxShape
{
	explicit FatBox(const btVector3& half) : btBoxShape(half) {}
	void getBoundingSphere(btVector3& center, btScalar& radius) const override
	{
		center.setValue(btScalar(1), btScalar(0), btScalar(0));
		radius = btScalar(100);
	}
};
}  // namespace

// Boxes of many sizes (tiny to huge, flat, zero-sized), margins (default, zero, large and clamped) and
// scalings: the inline value is the virtual one, bit for bit.
TEST(AngularMotionDisc, PlainBoxGivesTheVirtualValueBitForBit)
{
	std::mt19937 random(77);
	std::uniform_real_distribution<float> unit(0, 1);
	const btScalar sizes[] = {btScalar(0), btScalar(1e-6), btScalar(0.01), btScalar(0.5),
	                          btScalar(1), btScalar(3.7),  btScalar(1e3),  btScalar(1e6)};
	int compared = 0;
	for (int trial = 0; trial < 3000; ++trial)
	{
		const btScalar scale = sizes[trial % 8];
		btBoxShape box(btVector3(unit(random), unit(random), unit(random)) * scale);
		if (trial % 3 == 1) box.setMargin(btScalar(0));
		if (trial % 3 == 2) box.setMargin(scale * unit(random));  // may be clamped to the smallest extent
		if (trial % 5 == 0)
			box.setLocalScaling(
			    btVector3(btScalar(0.1) + unit(random), btScalar(0.1) + unit(random), btScalar(0.1) + unit(random)) *
			    btScalar(2));
		const btScalar expected = box.getAngularMotionDisc();
		const btScalar inlined = caliber::angularMotionDisc(&box);
		EXPECT_TRUE(sameBits(inlined, expected)) << trial << ": " << inlined << " against " << expected;
		++compared;
	}
	EXPECT_EQ(compared, 3000);
}

// A subclass of btBoxShape and other shapes are asked through the virtual call.
TEST(AngularMotionDisc, OtherShapesAndBoxSubclassesAreAsked)
{
	FatBox fat(btVector3(1, 2, 3));
	EXPECT_EQ(fat.getAngularMotionDisc(), btScalar(101));
	EXPECT_EQ(caliber::angularMotionDisc(&fat), btScalar(101));

	btSphereShape sphere(btScalar(0.75));
	EXPECT_TRUE(sameBits(caliber::angularMotionDisc(&sphere), sphere.getAngularMotionDisc()));
	// A plain box, for contrast: the outer half extents' length (margin included).
	btBoxShape box(btVector3(1, 2, 2));
	EXPECT_NEAR(caliber::angularMotionDisc(&box), btScalar(3), btScalar(1e-6));  // |(1, 2, 2)| = 3
}
