// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCompoundShape: AABB as the union of the children, the child tree against brute force through
// additions, removals and moves, the principal axes against the parallel axis theorem by hand, local
// scaling, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <set>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"

namespace
{
using shapes_core_test::Random;
using shapes_core_test::vectorsNear;

// Coordinates are of order 10: a few roundings of such values.
const btScalar kTol = btScalar(100) * SIMD_EPSILON * 10;

struct ChildCollector : btDbvt::ICollide
{
	using btDbvt::ICollide::Process;
	std::set<int> indices;
	void Process(const btDbvtNode* leaf) override { indices.insert(leaf->dataAsInt); }
};

// Every child has one leaf, whose index is the child's and whose box is the child's AABB; the tree holds
// nothing else; the local AABB is the union of the children's AABBs.
::testing::AssertionResult compoundIsConsistent(const btCompoundShape& compound)
{
	const btDbvt* tree = compound.getDynamicAabbTree();
	const int n = compound.getNumChildShapes();
	btVector3 unionMin(0, 0, 0), unionMax(0, 0, 0);
	for (int i = 0; i < n; ++i)
	{
		btVector3 lo, hi;
		compound.getChildShape(i)->getAabb(compound.getChildTransform(i), lo, hi);
		if (i == 0)
		{
			unionMin = lo;
			unionMax = hi;
		}
		else
		{
			unionMin.setMin(lo);
			unionMax.setMax(hi);
		}
		if (!tree) continue;
		const btDbvtNode* leaf = const_cast<btCompoundShape&>(compound).getChildList()[i].m_node;
		if (!leaf || !leaf->isleaf()) return ::testing::AssertionFailure() << "child " << i << " has no leaf";
		if (leaf->dataAsInt != i)
			return ::testing::AssertionFailure() << "leaf of child " << i << " says " << leaf->dataAsInt;
		if (NotEqual(leaf->volume, btDbvtVolume::FromMM(lo, hi)))
			return ::testing::AssertionFailure() << "leaf box of child " << i << " is stale";
	}
	if (tree && tree->m_leaves != n) return ::testing::AssertionFailure() << "tree has " << tree->m_leaves << " leaves";
	if (tree && btDbvt::countLeaves(tree->m_root) != n) return ::testing::AssertionFailure() << "countLeaves";
	btTransform identity;
	identity.setIdentity();
	btVector3 aabbMin, aabbMax;
	compound.getAabb(identity, aabbMin, aabbMax);
	const btVector3 m(compound.getMargin(), compound.getMargin(), compound.getMargin());
	if (!vectorsNear(aabbMin, unionMin - m, kTol) || !vectorsNear(aabbMax, unionMax + m, kTol))
		return ::testing::AssertionFailure() << "local AABB is not the union of the children";
	return ::testing::AssertionSuccess();
}

struct Scene
{
	std::vector<std::unique_ptr<btCollisionShape>> shapes;
	btCollisionShape* randomShape(Random& rng)
	{
		if (rng.uniform(0, 1) < btScalar(0.5))
			shapes.emplace_back(new btBoxShape(btVector3(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2),
			                                             rng.uniform(btScalar(0.2), 2))));
		else
			shapes.emplace_back(new btSphereShape(rng.uniform(btScalar(0.2), 2)));
		return shapes.back().get();
	}
};
}  // namespace

TEST(CompoundShape, AabbIsUnionOfChildAabbsUnderTheWorldTransform)
{
	Random rng(1);
	Scene scene;
	btCompoundShape compound;
	for (int i = 0; i < 20; ++i) compound.addChildShape(rng.transform(10), scene.randomShape(rng));
	ASSERT_TRUE(compoundIsConsistent(compound));
	// Under a translation the world AABB is exactly the union of the children's world AABBs.
	btTransform shift;
	shift.setIdentity();
	shift.setOrigin(btVector3(3, -4, 5));
	btVector3 lo, hi, ulo, uhi;
	compound.getAabb(shift, lo, hi);
	for (int i = 0; i < compound.getNumChildShapes(); ++i)
	{
		btVector3 clo, chi;
		compound.getChildShape(i)->getAabb(shift * compound.getChildTransform(i), clo, chi);
		if (i == 0)
		{
			ulo = clo;
			uhi = chi;
		}
		ulo.setMin(clo);
		uhi.setMax(chi);
	}
	EXPECT_TRUE(vectorsNear(lo, ulo, kTol));
	EXPECT_TRUE(vectorsNear(hi, uhi, kTol));
	// Under a rotation it contains every child's world AABB.
	const btTransform t = rng.transform(5);
	compound.getAabb(t, lo, hi);
	for (int i = 0; i < compound.getNumChildShapes(); ++i)
	{
		btVector3 clo, chi;
		compound.getChildShape(i)->getAabb(t * compound.getChildTransform(i), clo, chi);
		for (int a = 0; a < 3; ++a)
		{
			EXPECT_LE(lo[a], clo[a] + kTol);
			EXPECT_GE(hi[a], chi[a] - kTol);
		}
	}
	// The margin grows the box on every side.
	compound.setMargin(btScalar(0.25));
	EXPECT_EQ(compound.getMargin(), btScalar(0.25));
	ASSERT_TRUE(compoundIsConsistent(compound));
}

TEST(CompoundShape, TreeQueriesMatchBruteForceThroughRemoveAndUpdate)
{
	Random rng(2);
	Scene scene;
	btCompoundShape compound;
	std::vector<btCollisionShape*> shared;
	for (int i = 0; i < 3; ++i) shared.push_back(scene.randomShape(rng));
	for (int i = 0; i < 60; ++i)
		compound.addChildShape(rng.transform(15), i % 5 == 0 ? shared[i % 3] : scene.randomShape(rng));
	ASSERT_TRUE(compoundIsConsistent(compound));
	for (int step = 0; step < 120; ++step)
	{
		const int n = compound.getNumChildShapes();
		const btScalar choice = rng.uniform(0, 1);
		const int index = std::min(n - 1, int(rng.uniform(0, btScalar(n))));
		const int revision = compound.getUpdateRevision();
		if (choice < btScalar(0.3))
		{
			compound.removeChildShapeByIndex(index);
			EXPECT_EQ(compound.getNumChildShapes(), n - 1);
			EXPECT_GT(compound.getUpdateRevision(), revision);
		}
		else if (choice < btScalar(0.7))
			compound.updateChildTransform(index, rng.transform(15), step % 2 == 0);
		else
			compound.addChildShape(rng.transform(15), scene.randomShape(rng));
		if (step % 2 == 1) compound.recalculateLocalAabb();  // after a move without recalculation
		ASSERT_TRUE(compoundIsConsistent(compound)) << "step " << step;

		const btDbvtVolume query = btDbvtVolume::FromCE(rng.vector(15), btVector3(4, 4, 4));
		ChildCollector hits;
		compound.getDynamicAabbTree()->collideTV(compound.getDynamicAabbTree()->m_root, query, hits);
		std::set<int> expected;
		for (int i = 0; i < compound.getNumChildShapes(); ++i)
		{
			btVector3 lo, hi;
			compound.getChildShape(i)->getAabb(compound.getChildTransform(i), lo, hi);
			bool overlap = true;
			for (int a = 0; a < 3; ++a) overlap = overlap && lo[a] <= query.Maxs()[a] && hi[a] >= query.Mins()[a];
			if (overlap) expected.insert(i);
		}
		EXPECT_EQ(hits.indices, expected) << "step " << step;
	}
}

TEST(CompoundShape, RemoveChildShapeRemovesEveryChildOfThatShape)
{
	Random rng(3);
	Scene scene;
	btCompoundShape compound;
	btCollisionShape* repeated = scene.randomShape(rng);
	for (int i = 0; i < 12; ++i)
		compound.addChildShape(rng.transform(5), i % 3 == 0 ? repeated : scene.randomShape(rng));
	compound.removeChildShape(repeated);
	EXPECT_EQ(compound.getNumChildShapes(), 8);
	for (int i = 0; i < compound.getNumChildShapes(); ++i) EXPECT_NE(compound.getChildShape(i), repeated);
	ASSERT_TRUE(compoundIsConsistent(compound));
	// Removing everything leaves the empty compound.
	while (compound.getNumChildShapes() > 0) compound.removeChildShapeByIndex(0);
	ASSERT_TRUE(compoundIsConsistent(compound));
	EXPECT_TRUE(compound.getDynamicAabbTree()->empty());
}

TEST(CompoundShape, PrincipalAxesOfTwoBoxesSideBySideMatchParallelAxisTheorem)
{
	// Unit cubes (half extents 1, margin inside) centred at x = -2 (mass 1) and x = +2 (mass 3).
	btBoxShape cube(btVector3(1, 1, 1));
	btCompoundShape compound;
	btTransform left, right;
	left.setIdentity();
	left.setOrigin(btVector3(-2, 0, 0));
	right.setIdentity();
	right.setOrigin(btVector3(2, 0, 0));
	compound.addChildShape(left, &cube);
	compound.addChildShape(right, &cube);
	const btScalar masses[2] = {1, 3};
	btTransform principal;
	btVector3 inertia;
	compound.calculatePrincipalAxisTransform(masses, principal, inertia);
	// Centre of mass: (1 * -2 + 3 * 2) / 4 = 1. Each cube about its centre: m (2^2 + 2^2) / 12 = 2m/3.
	// About x through the centre of mass: 2/3 + 2 = 8/3. About y and z: 8/3 + 1 * 3^2 + 3 * 1^2 = 8/3 + 12.
	EXPECT_TRUE(vectorsNear(principal.getOrigin(), btVector3(1, 0, 0), kTol));
	const btScalar ixx = btScalar(8) / 3, iyy = btScalar(8) / 3 + 12;
	// The moments may come in any order and the axes with any sign: compare R diag(I) R^T with the tensor.
	const btMatrix3x3& r = principal.getBasis();
	const btMatrix3x3 tensor = r.scaled(inertia) * r.transpose();
	const btMatrix3x3 expected(ixx, 0, 0, 0, iyy, 0, 0, 0, iyy);
	for (int i = 0; i < 3; ++i) EXPECT_TRUE(vectorsNear(tensor[i], expected[i], kTol * 20)) << "row " << i;
	std::vector<btScalar> moments = {inertia.x(), inertia.y(), inertia.z()};
	std::sort(moments.begin(), moments.end());
	EXPECT_NEAR(moments[0], ixx, kTol * 20);
	EXPECT_NEAR(moments[2], iyy, kTol * 20);
	// The basis is a rotation.
	EXPECT_NEAR(r.determinant(), btScalar(1), kTol);
}

TEST(CompoundShape, PrincipalAxesFollowARotatedLayout)
{
	// The same two cubes, the whole layout rotated by q: the centre of mass rotates and the tensor becomes
	// q diag(8/3, 8/3 + 12, 8/3 + 12) q^T (each cube's own tensor is isotropic, so its rotation is irrelevant).
	const btQuaternion q(btVector3(1, 2, 3).normalized(), btScalar(0.7));
	const btMatrix3x3 rq(q);
	btBoxShape cube(btVector3(1, 1, 1));
	btCompoundShape compound;
	compound.addChildShape(btTransform(q, rq * btVector3(-2, 0, 0)), &cube);
	compound.addChildShape(btTransform(q, rq * btVector3(2, 0, 0)), &cube);
	const btScalar masses[2] = {1, 3};
	btTransform principal;
	btVector3 inertia;
	compound.calculatePrincipalAxisTransform(masses, principal, inertia);
	EXPECT_TRUE(vectorsNear(principal.getOrigin(), rq * btVector3(1, 0, 0), kTol));
	const btScalar ixx = btScalar(8) / 3, iyy = btScalar(8) / 3 + 12;
	const btMatrix3x3 expected = rq.scaled(btVector3(ixx, iyy, iyy)) * rq.transpose();
	const btMatrix3x3 got = principal.getBasis().scaled(inertia) * principal.getBasis().transpose();
	// Jacobi stops at a relative off-diagonal of 1e-6 of the largest moment (~15).
	for (int i = 0; i < 3; ++i) EXPECT_TRUE(vectorsNear(got[i], expected[i], btScalar(1e-3))) << "row " << i;
}

TEST(CompoundShape, LocalScalingScalesChildOriginsAndChildren)
{
	btBoxShape box(btVector3(1, 1, 1));
	btCompoundShape compound;
	btTransform t;
	t.setIdentity();
	t.setOrigin(btVector3(2, 0, 0));
	compound.addChildShape(t, &box);
	compound.setLocalScaling(btVector3(2, 3, 4));
	EXPECT_TRUE(vectorsNear(compound.getLocalScaling(), btVector3(2, 3, 4), 0));
	EXPECT_TRUE(vectorsNear(compound.getChildTransform(0).getOrigin(), btVector3(4, 0, 0), kTol));
	EXPECT_TRUE(vectorsNear(box.getLocalScaling(), btVector3(2, 3, 4), kTol));
	ASSERT_TRUE(compoundIsConsistent(compound));
	btTransform identity;
	identity.setIdentity();
	btVector3 lo, hi;
	compound.getAabb(identity, lo, hi);
	// The box's outer half extents become (2, 3, 4) around (4, 0, 0).
	EXPECT_TRUE(vectorsNear(lo, btVector3(2, -3, -4), kTol));
	EXPECT_TRUE(vectorsNear(hi, btVector3(6, 3, 4), kTol));
	// Scaling back to 1 restores the layout: the ratio is taken against the previous scaling.
	compound.setLocalScaling(btVector3(1, 1, 1));
	EXPECT_TRUE(vectorsNear(compound.getChildTransform(0).getOrigin(), btVector3(2, 0, 0), kTol));
	EXPECT_TRUE(vectorsNear(box.getLocalScaling(), btVector3(1, 1, 1), kTol));
}

TEST(CompoundShape, LocalInertiaIsTheAabbBoxInertia)
{
	btBoxShape box(btVector3(1, 2, 3));
	btCompoundShape compound;
	btTransform t;
	t.setIdentity();
	t.setOrigin(btVector3(1, 0, 0));
	compound.addChildShape(t, &box);
	btVector3 inertia;
	compound.calculateLocalInertia(12, inertia);
	// Sides 2, 4, 6: m/12 (b^2 + c^2) and so on (the offset of the child is ignored by this approximation).
	EXPECT_TRUE(vectorsNear(inertia, btVector3(16 + 36, 4 + 36, 4 + 16), kTol * 50));
}

TEST(CompoundShape, TreeCanBeDisabledAndCreatedLater)
{
	Random rng(4);
	Scene scene;
	btCompoundShape compound(false, 16);
	EXPECT_EQ(compound.getDynamicAabbTree(), nullptr);
	for (int i = 0; i < 10; ++i) compound.addChildShape(rng.transform(5), scene.randomShape(rng));
	EXPECT_EQ(compound.getChildList()[3].m_node, nullptr);
	compound.removeChildShapeByIndex(2);
	compound.updateChildTransform(1, rng.transform(5));
	ASSERT_TRUE(compoundIsConsistent(compound));
	compound.createAabbTreeFromChildren();
	ASSERT_NE(compound.getDynamicAabbTree(), nullptr);
	ASSERT_TRUE(compoundIsConsistent(compound));
	EXPECT_EQ(compound.getShapeType(), COMPOUND_SHAPE_PROXYTYPE);
	EXPECT_TRUE(compound.isCompound());
	EXPECT_STREQ(compound.getName(), "Compound");
}

TEST(CompoundShape, EmptyCompoundHasFiniteAabbAndZeroInertia)
{
	btCompoundShape compound;
	btTransform t;
	t.setIdentity();
	t.setOrigin(btVector3(1, 2, 3));
	btVector3 lo, hi;
	compound.getAabb(t, lo, hi);
	EXPECT_TRUE(vectorsNear(lo, btVector3(1, 2, 3), 0));
	EXPECT_TRUE(vectorsNear(hi, btVector3(1, 2, 3), 0));
	btVector3 inertia;
	compound.calculateLocalInertia(5, inertia);
	EXPECT_TRUE(vectorsNear(inertia, btVector3(0, 0, 0), 0));
	btTransform principal;
	compound.calculatePrincipalAxisTransform(0, principal, inertia);
	EXPECT_TRUE(vectorsNear(principal.getOrigin(), btVector3(0, 0, 0), 0));
	EXPECT_TRUE(vectorsNear(inertia, btVector3(0, 0, 0), 0));
	EXPECT_EQ(compound.getChildList(), nullptr);
}

TEST(CompoundShape, BadInputIsRejected)
{
	btSphereShape sphere(1);
	btCompoundShape compound;
	btTransform t;
	t.setIdentity();
	btTransform nanTransform = t;
	nanTransform.setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0));
	compound.addChildShape(t, &sphere);
	const btScalar negative[1] = {-1};
	btTransform principal;
	btVector3 inertia;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(compound.addChildShape(t, 0), "assertion failed");
	EXPECT_DEATH(compound.addChildShape(nanTransform, &sphere), "assertion failed");
	EXPECT_DEATH(compound.removeChildShapeByIndex(5), "assertion failed");
	EXPECT_DEATH(compound.updateChildTransform(-1, t), "assertion failed");
	EXPECT_DEATH(compound.updateChildTransform(0, nanTransform), "assertion failed");
	EXPECT_DEATH(compound.calculatePrincipalAxisTransform(negative, principal, inertia), "assertion failed");
	EXPECT_DEATH(compound.setLocalScaling(btVector3(0, 1, 1)), "assertion failed");
	EXPECT_DEATH(compound.getChildTransform(3), "assertion failed");
#else
	compound.addChildShape(t, 0);
	compound.addChildShape(nanTransform, &sphere);
	EXPECT_EQ(compound.getNumChildShapes(), 1);
	compound.removeChildShapeByIndex(5);
	compound.updateChildTransform(-1, t);
	compound.updateChildTransform(0, nanTransform);
	EXPECT_EQ(compound.getNumChildShapes(), 1);
	EXPECT_TRUE(vectorsNear(compound.getChildTransform(0).getOrigin(), btVector3(0, 0, 0), 0));
	compound.calculatePrincipalAxisTransform(negative, principal, inertia);
	EXPECT_TRUE(vectorsNear(principal.getOrigin(), btVector3(0, 0, 0), 0));
	EXPECT_TRUE(vectorsNear(principal.getBasis()[0], btVector3(1, 0, 0), 0));
	EXPECT_TRUE(vectorsNear(inertia, btVector3(0, 0, 0), 0));
	const btScalar zero[1] = {0};
	compound.calculatePrincipalAxisTransform(zero, principal, inertia);
	EXPECT_TRUE(vectorsNear(inertia, btVector3(0, 0, 0), 0));
	compound.setLocalScaling(btVector3(0, 1, 1));
	EXPECT_TRUE(vectorsNear(compound.getLocalScaling(), btVector3(1, 1, 1), 0));
	EXPECT_TRUE(vectorsNear(compound.getChildTransform(3).getOrigin(), btVector3(0, 0, 0), 0));
	EXPECT_EQ(compound.getChildShape(3), nullptr);
#endif
	ASSERT_TRUE(compoundIsConsistent(compound));
	// A non-finite world transform gives the documented overflow box.
#if !CALIBER_ASSERTS_ENABLED
	btVector3 lo, hi;
	compound.getAabb(nanTransform, lo, hi);
	EXPECT_EQ(lo.x(), -btScalar(BT_LARGE_FLOAT));
	EXPECT_EQ(hi.x(), btScalar(BT_LARGE_FLOAT));
#endif
}
