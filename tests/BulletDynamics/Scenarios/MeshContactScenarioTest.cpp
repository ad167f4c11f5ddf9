// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Contact fidelity of convex shapes on triangle meshes and height fields: a box resting on a mesh
// gets a whole face manifold at once (a hull too), a box or hull hitting a mesh at 120 m/s (straight, at an
// angle, turned onto an edge) stops at the surface instead of sinking into it, a resting hull prism does
// not creep, a hull lying across ridges is held at the ridges, and bodies sliding across a mesh of many
// small triangles do not catch on the edges between them.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "../Dynamics/DynamicsWorldTestUtil.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kStep = btScalar(1. / 60.);

// Static floors whose top is the plane y = 0. The test owns the mesh data; the world owns the shapes.
struct Floor
{
	std::unique_ptr<btTriangleMesh> triangles;
	std::vector<float> heights;
	btRigidBody* body = 0;
};

enum FloorKind
{
	kTwoTriangles,  // two triangles 1 km across: the box never meets an edge
	kFineGrid,      // 0.25 m cells: every face of the box spans many triangles and edges
	kGrid,          // 1 m cells, 160 m across
	kHeightField    // 1 m cells, flat
};

const char* floorName(FloorKind kind)
{
	switch (kind)
	{
		case kTwoTriangles:
			return "two large triangles";
		case kFineGrid:
			return "fine grid mesh";
		case kGrid:
			return "grid mesh";
		default:
			return "height field";
	}
}

void addGridTriangles(btTriangleMesh& triangles, btScalar halfSize, btScalar cell)
{
	const int cells = int(2 * halfSize / cell + btScalar(0.5));
	for (int j = 0; j < cells; ++j)
		for (int i = 0; i < cells; ++i)
		{
			const btScalar x0 = -halfSize + cell * btScalar(i), z0 = -halfSize + cell * btScalar(j);
			const btVector3 a(x0, 0, z0), b(x0 + cell, 0, z0), c(x0 + cell, 0, z0 + cell), d(x0, 0, z0 + cell);
			// Counter-clockwise seen from above: normals face +y.
			triangles.addTriangle(a, d, c);
			triangles.addTriangle(a, c, b);
		}
}

void addFloor(TestWorld& w, Floor& floor, FloorKind kind, btScalar friction)
{
	btCollisionShape* shape = 0;
	if (kind == kHeightField)
	{
		const int samples = 61;
		floor.heights.assign(samples * samples, 0.0f);
		// Heights in [-1, 1]: the shape is centred on its box, so height 0 is at y = 0.
		shape = w.shape<btHeightfieldTerrainShape>(samples, samples, floor.heights.data(), btScalar(-1), btScalar(1), 1,
		                                           false);
	}
	else
	{
		floor.triangles.reset(new btTriangleMesh());
		if (kind == kTwoTriangles)
		{
			floor.triangles->addTriangle(btVector3(-500, 0, -500), btVector3(-500, 0, 500), btVector3(500, 0, 500));
			floor.triangles->addTriangle(btVector3(-500, 0, -500), btVector3(500, 0, 500), btVector3(500, 0, -500));
		}
		else if (kind == kFineGrid)
			addGridTriangles(*floor.triangles, 12, btScalar(0.25));
		else
			addGridTriangles(*floor.triangles, 80, 1);
		shape = w.shape<btBvhTriangleMeshShape>(floor.triangles.get(), true);
	}
	floor.body = w.addBody(shape, 0, btVector3(0, 0, 0));
	floor.body->setFriction(friction);
}

// How far the box's lowest corner is below y = 0 (0 when it is above); `growth` is how far the surface lies
// beyond the corners (a hull's margin).
btScalar cornerDepth(const btRigidBody& box, const btVector3& halfExtents, btScalar growth = 0)
{
	btScalar lowest = BT_LARGE_FLOAT;
	for (int corner = 0; corner < 8; ++corner)
	{
		const btVector3 local((corner & 1) ? halfExtents.x() : -halfExtents.x(),
		                      (corner & 2) ? halfExtents.y() : -halfExtents.y(),
		                      (corner & 4) ? halfExtents.z() : -halfExtents.z());
		lowest = btMin(lowest, box.getWorldTransform()(local).y());
	}
	return btMax(btScalar(0), growth - lowest);
}

// A convex hull of the 8 corners of a box (the world owns it): a polyhedral shape without the box's
// closed forms, with its margin on top.
btConvexHullShape* hullBox(TestWorld& w, const btVector3& half)
{
	btConvexHullShape* corners = w.shape<btConvexHullShape>();
	for (int corner = 0; corner < 8; ++corner)
		corners->addPoint(btVector3((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
		                            (corner & 4) ? half.z() : -half.z()),
		                  corner == 7);
	return corners;
}

// The contact points between body and floor: their count and the area of the rectangle their x and z span.
struct ManifoldSpan
{
	int points = 0;
	btScalar spanX = 0, spanZ = 0;
};

ManifoldSpan manifoldSpan(TestWorld& w, const btRigidBody* body, const btRigidBody* floor)
{
	ManifoldSpan span;
	btScalar minX = BT_LARGE_FLOAT, maxX = -BT_LARGE_FLOAT, minZ = BT_LARGE_FLOAT, maxZ = -BT_LARGE_FLOAT;
	btDispatcher* dispatcher = w.world()->getDispatcher();
	for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
	{
		const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
		const bool ours = (manifold->getBody0() == body && manifold->getBody1() == floor) ||
		                  (manifold->getBody0() == floor && manifold->getBody1() == body);
		if (!ours) continue;
		for (int p = 0; p < manifold->getNumContacts(); ++p)
		{
			const btManifoldPoint& point = manifold->getContactPoint(p);
			// Only touching points count for resting support (speculative ones are farther than this).
			if (point.getDistance() > btScalar(0.01)) continue;
			++span.points;
			const btVector3& at = point.getPositionWorldOnB();
			minX = btMin(minX, at.x());
			maxX = btMax(maxX, at.x());
			minZ = btMin(minZ, at.z());
			maxZ = btMax(maxZ, at.z());
		}
	}
	if (span.points > 0)
	{
		span.spanX = maxX - minX;
		span.spanZ = maxZ - minZ;
	}
	return span;
}

// A unit box (half extents 0.5, mass 1) launched at the floor from 3 m above it at 120 m/s (2 m per step),
// in direction (sin a, -cos a, 0), turned by `tilt` about the z axis. Returns the deepest any corner got
// below the surface during the two seconds after launch, the most mechanical energy it had after the
// launch step, and its motion and height 10 s after launch.
struct ImpactOutcome
{
	btScalar deepest = 0;
	btScalar launchEnergy = 0;
	btScalar highestEnergy = 0;
	btScalar finalSpeed = 0;
	btScalar finalSpin = 0;
	btScalar finalY = 0;
};

btScalar mechanicalEnergy(const btRigidBody& body, btScalar gravity)
{
	const btVector3 w = body.getAngularVelocity();
	const btVector3 spinMomentum = body.getInvInertiaTensorWorld().inverse() * w;
	return btScalar(0.5) * body.getLinearVelocity().length2() / body.getInvMass() +
	       btScalar(0.5) * w.dot(spinMomentum) + gravity * body.getCenterOfMassPosition().y() / body.getInvMass();
}

ImpactOutcome launchBoxAtFloor(FloorKind kind, btScalar angleFromVertical, btScalar tilt, bool hull = false,
                               bool polyhedron = false)
{
	TestWorld w;
	Floor floor;
	// Friction 1 against 1: the impact's normal impulse can stop the sliding part of a 45 degree hit.
	addFloor(w, floor, kind, 1);
	const btVector3 halfExtents(btScalar(0.5), btScalar(0.5), btScalar(0.5));
	btConvexShape* shape = 0;
	if (hull)
	{
		btConvexHullShape* corners = hullBox(w, halfExtents);
		if (polyhedron) corners->initializePolyhedralFeatures();
		shape = corners;
	}
	else
	{
		shape = w.shape<btBoxShape>(halfExtents);
	}
	// A hull's surface is its points' hull grown by the margin: depths are measured on that surface.
	const btScalar growth = hull ? shape->getMargin() : btScalar(0);
	btRigidBody* box = w.addBody(
	    shape, 1, btTransform(btQuaternion(btVector3(0, 0, 1), tilt), btVector3(-3 * btTan(angleFromVertical), 3, 0)));
	box->setFriction(1);
	box->setLinearVelocity(btVector3(btSin(angleFromVertical), -btCos(angleFromVertical), 0) * btScalar(120));
	const btScalar gravity = -w.world()->getGravity().y();
	ImpactOutcome outcome;
	outcome.launchEnergy = mechanicalEnergy(*box, gravity);
	for (int step = 0; step < 120; ++step)
	{
		w.run(1, kStep);
		outcome.deepest = btMax(outcome.deepest, cornerDepth(*box, halfExtents, growth));
		outcome.highestEnergy = btMax(outcome.highestEnergy, mechanicalEnergy(*box, gravity));
	}
	w.run(480, kStep);
	outcome.finalSpeed = box->getLinearVelocity().length();
	outcome.finalSpin = box->getAngularVelocity().length();
	outcome.finalY = box->getCenterOfMassPosition().y() - growth;
	return outcome;
}

// A speculative contact lets the box close the gap and no more, so what is left is the resting
// penetration the solver allows (Baumgarte slop, a few mm at 10 m/s^2); 1 cm is far below the 2 m it
// travels per step, and a box that sinks to its centre or passes through is caught with margin.
void expectNeverSinks(const ImpactOutcome& outcome)
{
	EXPECT_LT(outcome.deepest, btScalar(0.01)) << "deepest corner " << outcome.deepest << " m below the surface";
	// Contacts without restitution only take energy: more than it was launched with would mean a contact
	// pushed it out of the floor (a corner caught deep and thrown back).
	EXPECT_LE(outcome.highestEnergy, outcome.launchEnergy * btScalar(1.001))
	    << "energy " << outcome.highestEnergy << " J, launched with " << outcome.launchEnergy << " J";
}

void expectStopsAtTheSurface(FloorKind kind, btScalar angleFromVertical, btScalar tilt, bool hull = false,
                             bool polyhedron = false)
{
	const ImpactOutcome outcome = launchBoxAtFloor(kind, angleFromVertical, tilt, hull, polyhedron);
	SCOPED_TRACE(floorName(kind));
	expectNeverSinks(outcome);
	// At rest: no faster than gravity's pull over one step (1/6 m/s), so it is lying on something.
	EXPECT_LT(outcome.finalSpeed, btScalar(10) * kStep) << "final speed " << outcome.finalSpeed;
	EXPECT_LT(outcome.finalSpin, btScalar(0.5)) << "final angular speed " << outcome.finalSpin;
	// Lying on the floor on a face: centre half a side above it (within the 1 cm allowed above; a hull's
	// centre is its margin higher, taken off finalY).
	EXPECT_NEAR(outcome.finalY, btScalar(0.5), btScalar(0.01)) << "final centre height " << outcome.finalY;
}

// At 45 degrees the box lands with 85 m/s along the floor; friction 1 can just stop it, the torque about
// the leading edge just tips it, so it may tumble on for seconds (or off a finite floor): only that it
// never sinks in and gains no energy is physics.
void expectAngledHitNeverSinks(FloorKind kind, btScalar angleFromVertical)
{
	SCOPED_TRACE(floorName(kind));
	expectNeverSinks(launchBoxAtFloor(kind, angleFromVertical, 0));
}
}  // namespace

TEST(MeshContactScenario, BoxHittingATwoTriangleMeshStraightDownAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kTwoTriangles, 0, 0);
}

TEST(MeshContactScenario, BoxHittingAGridMeshStraightDownAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kGrid, 0, 0);
}

TEST(MeshContactScenario, BoxHittingAFineGridMeshStraightDownAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kFineGrid, 0, 0);
}

TEST(MeshContactScenario, BoxHittingATwoTriangleMeshAt45DegreesAt120MetresPerSecondNeverSinksIn)
{
	expectAngledHitNeverSinks(kTwoTriangles, SIMD_PI / 4);
}

TEST(MeshContactScenario, BoxHittingAGridMeshAt45DegreesAt120MetresPerSecondNeverSinksIn)
{
	expectAngledHitNeverSinks(kGrid, SIMD_PI / 4);
}

TEST(MeshContactScenario, TurnedBoxHittingATwoTriangleMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kTwoTriangles, 0, SIMD_PI / 6);
}

TEST(MeshContactScenario, TurnedBoxHittingAGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kGrid, 0, SIMD_PI / 6);
}

TEST(MeshContactScenario, TurnedBoxHittingAHeightFieldAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kHeightField, 0, SIMD_PI / 6);
}

// A hull of a box's corners falling at 120 m/s: GJK's single point per triangle let it sink; its clipped
// face holds it at its corners on the first (speculative) contact.
TEST(MeshContactScenario, HullBoxHittingAGridMeshStraightDownAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kGrid, 0, 0, true);
}

TEST(MeshContactScenario, HullBoxHittingAFineGridMeshStraightDownAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kFineGrid, 0, 0, true);
}

TEST(MeshContactScenario, HullBoxHittingAHeightFieldStraightDownAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kHeightField, 0, 0, true);
}

// A hull box turned 30 degrees lands on an edge and tips onto a face: the face coming down needs its
// speculative points before GJK's normal is the face's.
TEST(MeshContactScenario, TurnedHullBoxHittingATwoTriangleMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kTwoTriangles, 0, SIMD_PI / 6, true);
}

TEST(MeshContactScenario, TurnedHullBoxHittingAGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kGrid, 0, SIMD_PI / 6, true);
}

TEST(MeshContactScenario, TurnedHullBoxHittingAFineGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kFineGrid, 0, SIMD_PI / 6, true);
}

TEST(MeshContactScenario, TurnedHullBoxHittingAHeightFieldAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kHeightField, 0, SIMD_PI / 6, true);
}

TEST(MeshContactScenario, TurnedHullBoxWithPolyhedronHittingAGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kGrid, 0, SIMD_PI / 6, true, true);
}

TEST(MeshContactScenario, TurnedHullBoxWithPolyhedronHittingAHeightFieldAt120MetresPerSecondStopsAtTheSurface)
{
	expectStopsAtTheSurface(kHeightField, 0, SIMD_PI / 6, true, true);
}

namespace
{
// A box (or hull of the same box) placed 1 mm above the floor: after one step its manifold must already
// hold the four corners, and after two seconds it must lie flat where it landed.
void expectRestsFlatOnAFullManifold(FloorKind kind, bool hull, bool polyhedron = false)
{
	SCOPED_TRACE(floorName(kind));
	TestWorld w;
	Floor floor;
	addFloor(w, floor, kind, btScalar(0.5));
	const btScalar half = btScalar(0.5);
	btConvexShape* shape = 0;
	btScalar restingHeight = half;
	if (hull)
	{
		btConvexHullShape* corners = hullBox(w, btVector3(half, half, half));
		if (polyhedron) corners->initializePolyhedralFeatures();
		// A hull's surface is its points' hull grown by the margin.
		restingHeight += corners->getMargin();
		shape = corners;
	}
	else
	{
		shape = w.shape<btBoxShape>(btVector3(half, half, half));
	}
	// Off the cells' corners and turned about the vertical, so that the face crosses several triangles.
	const btVector3 start(btScalar(0.3), restingHeight + btScalar(0.001), btScalar(0.2));
	btRigidBody* body = w.addBody(shape, 1, btTransform(btQuaternion(btVector3(0, 1, 0), btScalar(0.3)), start));
	body->setActivationState(DISABLE_DEACTIVATION);

	w.run(1, kStep);
	const ManifoldSpan first = manifoldSpan(w, body, floor.body);
	// Four points at once, spanning the bottom face: turned by 0.3 rad, its corners span
	// 2 * 0.5 * (cos 0.3 + sin 0.3) = 1.25 m in x and in z; GJK's single point per triangle spans far less.
	EXPECT_GE(first.points, 4) << "points after one step: " << first.points;
	const btScalar span = 2 * half * (btCos(btScalar(0.3)) + btSin(btScalar(0.3)));
	EXPECT_NEAR(first.spanX, span, btScalar(0.01)) << "x span " << first.spanX;
	EXPECT_NEAR(first.spanZ, span, btScalar(0.01)) << "z span " << first.spanZ;

	w.run(119, kStep);
	const btVector3 settled = body->getCenterOfMassPosition();
	btScalar drift = 0, tilt = 0;
	for (int step = 0; step < 60; ++step)
	{
		w.run(1, kStep);
		drift = btMax(drift, (body->getCenterOfMassPosition() - settled).length());
		const btVector3 up = body->getWorldTransform().getBasis().getColumn(1);
		tilt = btMax(tilt, btAcos(btMin(btScalar(1), up.y())));
	}
	const ManifoldSpan resting = manifoldSpan(w, body, floor.body);
	EXPECT_GE(resting.points, 4) << "points at rest: " << resting.points;
	// Flat: a tilt of 1 mrad lifts a corner 1 mm; a body resting on one or two points rocks far more.
	EXPECT_LT(tilt, btScalar(0.001)) << "tilt " << tilt << " rad";
	// Steady: it stays where it settled to within 1 mm over a second (the solver's resting jitter is
	// micrometres; a body creeping or rocking on a partial manifold moves millimetres).
	EXPECT_LT(drift, btScalar(0.001)) << "drift " << drift << " m";
	// At the surface: its resting height within the solver's few-millimetre penetration slop.
	EXPECT_NEAR(settled.y(), restingHeight, btScalar(0.005)) << "resting centre height " << settled.y();
}
}  // namespace

TEST(MeshContactScenario, BoxRestingOnATwoTriangleMeshGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kTwoTriangles, false);
}

TEST(MeshContactScenario, BoxRestingOnAGridMeshGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kGrid, false);
}

TEST(MeshContactScenario, BoxRestingOnAHeightFieldGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kHeightField, false);
}

TEST(MeshContactScenario, HullRestingOnATwoTriangleMeshGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kTwoTriangles, true);
}

TEST(MeshContactScenario, HullRestingOnAHeightFieldGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kHeightField, true);
}

TEST(MeshContactScenario, HullRestingOnAFineGridMeshGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kFineGrid, true);
}

TEST(MeshContactScenario, HullWithPolyhedronRestingOnAGridMeshGetsAFullManifoldAndLiesFlat)
{
	expectRestsFlatOnAFullManifold(kGrid, true, true);
}

namespace
{
const int kPrismSides = 12;
const btScalar kPrismRadius = btScalar(0.5);

// A hull shaped like a cylinder (the world owns it): a 12-sided prism, radius 0.5, length 1.5, along x,
// with corners at angles (k + 1/2) 30 degrees around x from +y, so that the side face between 165 and 195
// degrees faces -y, flat at the bottom, at radius cos(15 degrees) from the axis.
btConvexHullShape* hullPrism(TestWorld& w, bool polyhedron)
{
	const btScalar halfLength = btScalar(0.75);
	btConvexHullShape* prism = w.shape<btConvexHullShape>();
	for (int k = 0; k < kPrismSides; ++k)
	{
		const btScalar angle = (btScalar(k) + btScalar(0.5)) * SIMD_2_PI / btScalar(kPrismSides);
		for (int end = 0; end < 2; ++end)
			prism->addPoint(
			    btVector3(end ? halfLength : -halfLength, kPrismRadius * btCos(angle), kPrismRadius * btSin(angle)),
			    false);
	}
	prism->recalcLocalAabb();
	if (polyhedron) prism->initializePolyhedralFeatures();
	return prism;
}

// The prism launched straight down at 120 m/s from 3 m, turned 15 degrees about its axis: it lands on
// the edge between two side faces, all along its length, and tips onto one of them. Returns how deep its
// surface (its points' hull grown by the margin) got during the two seconds after launch, and its motion
// 10 s after launch.
ImpactOutcome launchPrismAtFloor(FloorKind kind, bool polyhedron)
{
	TestWorld w;
	Floor floor;
	addFloor(w, floor, kind, 1);
	btConvexHullShape* prism = hullPrism(w, polyhedron);
	const btQuaternion turn(btVector3(1, 0, 0), SIMD_PI / 12);
	btRigidBody* body = w.addBody(prism, 1, btTransform(turn, btVector3(0, 3, 0)));
	body->setFriction(1);
	// Kept awake: tipping slowly from its edge onto a face it can fall below the sleeping thresholds (0.8 m/s
	// and 1 rad/s by default) and stop half-way, which is sleeping, not the contact.
	body->setActivationState(DISABLE_DEACTIVATION);
	body->setLinearVelocity(btVector3(0, -120, 0));
	const btScalar gravity = -w.world()->getGravity().y();
	ImpactOutcome outcome;
	outcome.launchEnergy = mechanicalEnergy(*body, gravity);
	for (int step = 0; step < 120; ++step)
	{
		w.run(1, kStep);
		btScalar lowest = BT_LARGE_FLOAT;
		for (int i = 0; i < prism->getNumPoints(); ++i)
			lowest = btMin(lowest, body->getWorldTransform()(prism->getUnscaledPoints()[i]).y());
		outcome.deepest = btMax(outcome.deepest, prism->getMargin() - lowest);
		outcome.highestEnergy = btMax(outcome.highestEnergy, mechanicalEnergy(*body, gravity));
	}
	w.run(480, kStep);
	outcome.finalSpeed = body->getLinearVelocity().length();
	outcome.finalSpin = body->getAngularVelocity().length();
	// Lying on a side face: the axis cos(15 degrees) of the radius above the surface.
	outcome.finalY = body->getCenterOfMassPosition().y() - prism->getMargin() -
	                 kPrismRadius * btCos(SIMD_PI / btScalar(kPrismSides));
	return outcome;
}

void expectPrismStopsAtTheSurface(FloorKind kind, bool polyhedron)
{
	SCOPED_TRACE(floorName(kind));
	const ImpactOutcome outcome = launchPrismAtFloor(kind, polyhedron);
	expectNeverSinks(outcome);
	// At rest on a side face (as for the box): slower than gravity's pull over a step, at its resting height.
	EXPECT_LT(outcome.finalSpeed, btScalar(10) * kStep) << "final speed " << outcome.finalSpeed;
	EXPECT_LT(outcome.finalSpin, btScalar(0.5)) << "final angular speed " << outcome.finalSpin;
	EXPECT_NEAR(outcome.finalY, btScalar(0), btScalar(0.01)) << "final height above resting " << outcome.finalY;
}
}  // namespace

TEST(MeshContactScenario, TurnedHullPrismHittingAGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectPrismStopsAtTheSurface(kGrid, false);
}

TEST(MeshContactScenario, TurnedHullPrismHittingAFineGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectPrismStopsAtTheSurface(kFineGrid, false);
}

TEST(MeshContactScenario, TurnedHullPrismHittingAHeightFieldAt120MetresPerSecondStopsAtTheSurface)
{
	expectPrismStopsAtTheSurface(kHeightField, false);
}

// With its polyhedron the prism's face was the most opposed one, also when tilted: of the two faces either
// side of the edge it lands on, one took speculative impulses from the solver's iterations at the landing,
// and the prism tipped onto it hard, 4 to 9 cm deep. Balanced on the edge it gets no tilted face.
TEST(MeshContactScenario, TurnedHullPrismWithPolyhedronHittingATwoTriangleMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectPrismStopsAtTheSurface(kTwoTriangles, true);
}

TEST(MeshContactScenario, TurnedHullPrismWithPolyhedronHittingAGridMeshAt120MetresPerSecondStopsAtTheSurface)
{
	expectPrismStopsAtTheSurface(kGrid, true);
}

TEST(MeshContactScenario, TurnedHullPrismWithPolyhedronHittingAHeightFieldAt120MetresPerSecondStopsAtTheSurface)
{
	expectPrismStopsAtTheSurface(kHeightField, true);
}

namespace
{
// A hull shaped like a cylinder (a 12-sided prism, radius 0.5, length 1.5, along x) lying on one of its
// side faces 1 mm above the floor, turned about the vertical. On GJK's single point per triangle it
// balances on a line and rocks or rolls; with its side face clipped it lies still where it landed.
void expectPrismLiesStill(FloorKind kind, bool polyhedron)
{
	SCOPED_TRACE(floorName(kind));
	TestWorld w;
	Floor floor;
	addFloor(w, floor, kind, btScalar(0.5));
	btConvexHullShape* prism = hullPrism(w, polyhedron);
	const btScalar restingHeight = kPrismRadius * btCos(SIMD_PI / btScalar(kPrismSides)) + prism->getMargin();
	const btScalar turn = btScalar(0.3);
	btRigidBody* body =
	    w.addBody(prism, 1,
	              btTransform(btQuaternion(btVector3(0, 1, 0), turn),
	                          btVector3(btScalar(0.3), restingHeight + btScalar(0.001), btScalar(0.2))));
	body->setActivationState(DISABLE_DEACTIVATION);
	w.run(1, kStep);
	const ManifoldSpan first = manifoldSpan(w, body, floor.body);
	EXPECT_GE(first.points, 4) << "points after one step: " << first.points;
	w.run(119, kStep);
	const btVector3 settled = body->getCenterOfMassPosition();
	const btQuaternion settledTurn = body->getOrientation();
	btScalar drift = 0, rotation = 0, spin = 0;
	for (int step = 0; step < 60; ++step)
	{
		w.run(1, kStep);
		drift = btMax(drift, (body->getCenterOfMassPosition() - settled).length());
		rotation = btMax(rotation, body->getOrientation().angleShortestPath(settledTurn));
		spin = btMax(spin, body->getAngularVelocity().length());
	}
	// Still: within 0.2 mm over a second. The solver's resting noise (about 1e-3 rad/s of rocking on the
	// narrow face, reversing every step) moves it by tens of micrometres back and forth; a one-way creep
	// (1 mm/s when the manifold's points were solved in diagonal pairs) adds up past the bound. No rolling
	// (1 mm of roll at this radius is 2 mrad) and no rocking (1 mrad of rock lifts the face's edge by 0.25 mm).
	EXPECT_LT(drift, btScalar(0.0002)) << "drift " << drift << " m";
	EXPECT_LT(rotation, btScalar(0.001)) << "rotation " << rotation << " rad";
	EXPECT_LT(spin, btScalar(0.004)) << "angular speed " << spin << " rad/s";
	EXPECT_NEAR(settled.y(), restingHeight, btScalar(0.005)) << "resting centre height " << settled.y();
}
}  // namespace

TEST(MeshContactScenario, HullPrismLyingOnATwoTriangleMeshLiesStill) { expectPrismLiesStill(kTwoTriangles, false); }

TEST(MeshContactScenario, HullPrismLyingOnAFineGridMeshLiesStill) { expectPrismLiesStill(kFineGrid, false); }

TEST(MeshContactScenario, HullPrismLyingOnAHeightFieldLiesStill) { expectPrismLiesStill(kHeightField, false); }

TEST(MeshContactScenario, HullPrismWithPolyhedronLyingOnAGridMeshLiesStill) { expectPrismLiesStill(kGrid, true); }

namespace
{
// A hull of a 1 x 0.5 x 1 box (with or without its polyhedron) laid flat across two parallel ridges of a
// mesh: ridges along z at x = +-0.3 and height 0, the mesh falling away 10 degrees on both sides of each
// (a valley between them, slopes outside). The hull's face touches only the ridges' edges, never a
// triangle's face. Turned about the vertical so that the face's sides cross the ridges at an angle.
void expectHullAcrossRidgesLiesStill(bool polyhedron, btScalar turn)
{
	TestWorld w;
	btTriangleMesh ridges;
	const btScalar half = 5, ridge = btScalar(0.3), slope = btTan(btScalar(0.17));
	const btScalar xs[5] = {-half, -ridge, 0, ridge, half};
	const btScalar ys[5] = {-(half - ridge) * slope, 0, -ridge * slope, 0, -(half - ridge) * slope};
	for (int i = 0; i < 4; ++i)
	{
		const btVector3 a(xs[i], ys[i], -half), b(xs[i + 1], ys[i + 1], -half), c(xs[i + 1], ys[i + 1], half),
		    d(xs[i], ys[i], half);
		ridges.addTriangle(a, d, c);
		ridges.addTriangle(a, c, b);
	}
	btRigidBody* floor = w.addBody(w.shape<btBvhTriangleMeshShape>(&ridges, true), 0, btVector3(0, 0, 0));
	floor->setFriction(btScalar(0.5));
	btConvexHullShape* hull = hullBox(w, btVector3(btScalar(0.5), btScalar(0.25), btScalar(0.5)));
	if (polyhedron) hull->initializePolyhedralFeatures();
	const btScalar restingHeight = btScalar(0.25) + hull->getMargin();
	btRigidBody* body = w.addBody(
	    hull, 1, btTransform(btQuaternion(btVector3(0, 1, 0), turn), btVector3(0, restingHeight + btScalar(0.001), 0)));
	body->setFriction(btScalar(0.5));
	body->setActivationState(DISABLE_DEACTIVATION);
	w.run(1, kStep);
	// Held where the face crosses the ridges, along the face's normal (straight up): the ends of the two
	// ridges' segments under the face. Along a sloping triangle's normal (10 degrees off) the two ridges
	// push the hull sideways against each other.
	int upright = 0;
	btDispatcher* dispatcher = w.world()->getDispatcher();
	for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
	{
		const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
		for (int p = 0; p < manifold->getNumContacts(); ++p)
			upright += manifold->getContactPoint(p).m_normalWorldOnB.y() > btScalar(0.9999);
	}
	EXPECT_EQ(upright, 4) << "points with the face's normal after one step";
	w.run(179, kStep);
	const btVector3 settled = body->getCenterOfMassPosition();
	btScalar drift = 0, tilt = 0, lowest = BT_LARGE_FLOAT;
	for (int step = 0; step < 120; ++step)
	{
		w.run(1, kStep);
		drift = btMax(drift, (body->getCenterOfMassPosition() - settled).length());
		const btVector3 up = body->getWorldTransform().getBasis().getColumn(1);
		tilt = btMax(tilt, btAcos(btMin(btScalar(1), up.y())));
		lowest = btMin(lowest, body->getCenterOfMassPosition().y());
	}
	// Lying on the ridges: level (a tilt of 1 mrad lifts one side 1 mm), at its resting height (the
	// solver's resting penetration is well under a millimetre; rocking about GJK's single point per
	// triangle let it sink 3 mm), and still: within 0.2 mm over two seconds (resting jitter is micrometres;
	// on GJK's points it crept 2.6 mm and turned 20 mrad).
	EXPECT_LT(tilt, btScalar(0.001)) << "tilt " << tilt << " rad";
	EXPECT_NEAR(lowest, restingHeight, btScalar(0.001)) << "lowest centre height " << lowest;
	EXPECT_LT(drift, btScalar(0.0002)) << "drift " << drift << " m";
}
}  // namespace

TEST(MeshContactScenario, HullAcrossTwoRidgesIsHeldAtTheRidgesAlongItsFaceNormalAndLiesStill)
{
	expectHullAcrossRidgesLiesStill(false, btScalar(0.4));
	expectHullAcrossRidgesLiesStill(false, btScalar(0.8));
}

TEST(MeshContactScenario, HullWithPolyhedronAcrossTwoRidgesIsHeldAtTheRidgesAlongItsFaceNormalAndLiesStill)
{
	expectHullAcrossRidgesLiesStill(true, btScalar(0.4));
}

namespace
{
// A capsule (radius 0.25, core 1 m) lying on its side 1 mm above the floor, turned about the vertical:
// after one step its manifold holds both ends of the core, and it lies still where it landed (on a
// single point per triangle it balances on the middle and rolls or rocks).
void expectCapsuleRestsOnBothEnds(FloorKind kind)
{
	SCOPED_TRACE(floorName(kind));
	TestWorld w;
	Floor floor;
	addFloor(w, floor, kind, btScalar(0.5));
	const btScalar radius = btScalar(0.25), core = 1;
	const btScalar turn = btScalar(0.3);
	btRigidBody* body = w.addBody(w.shape<btCapsuleShapeX>(radius, core), 1,
	                              btTransform(btQuaternion(btVector3(0, 1, 0), turn),
	                                          btVector3(btScalar(0.3), radius + btScalar(0.001), btScalar(0.2))));
	body->setActivationState(DISABLE_DEACTIVATION);
	w.run(1, kStep);
	const ManifoldSpan first = manifoldSpan(w, body, floor.body);
	EXPECT_GE(first.points, 2) << "points after one step: " << first.points;
	// The core's ends seen from below: cos and sin of the turn along x and z (1 cm for rounding and the
	// millimetre it drops).
	EXPECT_NEAR(first.spanX, core * btCos(turn), btScalar(0.01)) << "x span " << first.spanX;
	EXPECT_NEAR(first.spanZ, core * btSin(turn), btScalar(0.01)) << "z span " << first.spanZ;

	w.run(119, kStep);
	const btVector3 settled = body->getCenterOfMassPosition();
	btScalar drift = 0, spin = 0;
	for (int step = 0; step < 60; ++step)
	{
		w.run(1, kStep);
		drift = btMax(drift, (body->getCenterOfMassPosition() - settled).length());
		spin = btMax(spin, body->getAngularVelocity().length());
	}
	// Still: within 1 mm over a second, and no rolling (a roll of 1 mm/s is 4 mrad/s at this radius).
	EXPECT_LT(drift, btScalar(0.001)) << "drift " << drift << " m";
	EXPECT_LT(spin, btScalar(0.004)) << "angular speed " << spin << " rad/s";
	EXPECT_NEAR(settled.y(), radius, btScalar(0.005)) << "resting centre height " << settled.y();
}
}  // namespace

TEST(MeshContactScenario, CapsuleLyingOnATwoTriangleMeshRestsOnBothEnds)
{
	expectCapsuleRestsOnBothEnds(kTwoTriangles);
}

TEST(MeshContactScenario, CapsuleLyingOnAGridMeshRestsOnBothEnds) { expectCapsuleRestsOnBothEnds(kGrid); }

TEST(MeshContactScenario, CapsuleLyingOnAHeightFieldRestsOnBothEnds) { expectCapsuleRestsOnBothEnds(kHeightField); }

namespace
{
// A body resting on the fine grid (0.25 m cells, edges every 25 cm along x and z and diagonals) is set
// sliding at 10 m/s along `direction` with no friction anywhere. Over one second nothing should touch it
// but the floor's support: its speed must stay 10 m/s and it must not be thrown up by an edge.
struct SlideOutcome
{
	btScalar slowestSpeed = BT_LARGE_FLOAT;
	btScalar fastestSpeed = 0;
	btScalar highestRise = 0;
};

SlideOutcome slideAcrossFineGrid(btConvexShape* shape, btScalar restingHeight, TestWorld& w, const btVector3& direction,
                                 bool rolling)
{
	Floor floor;
	addFloor(w, floor, kFineGrid, rolling ? btScalar(1) : btScalar(0));
	btRigidBody* body = w.addBody(shape, 1, btVector3(-5, restingHeight, btScalar(-0.1)));
	body->setFriction(rolling ? btScalar(1) : btScalar(0));
	body->setActivationState(DISABLE_DEACTIVATION);
	w.run(30, kStep);
	const btScalar settledY = body->getCenterOfMassPosition().y();
	const btScalar speed = 10;
	body->setLinearVelocity(direction.normalized() * speed);
	if (rolling)
	{
		// Rolling without slipping: the contact point is at rest, spin = v / r about direction x up.
		body->setAngularVelocity(btVector3(0, 1, 0).cross(direction.normalized()) * (speed / restingHeight));
	}
	SlideOutcome outcome;
	for (int step = 0; step < 60; ++step)
	{
		w.run(1, kStep);
		const btScalar v = body->getLinearVelocity().length();
		outcome.slowestSpeed = btMin(outcome.slowestSpeed, v);
		outcome.fastestSpeed = btMax(outcome.fastestSpeed, v);
		outcome.highestRise = btMax(outcome.highestRise, body->getCenterOfMassPosition().y() - settledY);
	}
	return outcome;
}

void expectSlidesUndisturbed(const SlideOutcome& outcome)
{
	// Nothing but the flat floor acts along the motion: an edge caught by a speculative or penetrating
	// contact brakes the body by metres per second; 1 % leaves room for the solver's rounding only.
	EXPECT_GT(outcome.slowestSpeed, btScalar(9.9)) << "slowest speed " << outcome.slowestSpeed;
	EXPECT_LT(outcome.fastestSpeed, btScalar(10.1)) << "fastest speed " << outcome.fastestSpeed;
	// A ghost hit on an edge throws the body up by centimetres; resting jitter is micrometres.
	EXPECT_LT(outcome.highestRise, btScalar(0.001)) << "rose " << outcome.highestRise << " m";
}
}  // namespace

TEST(MeshContactScenario, BoxSlidingAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	expectSlidesUndisturbed(slideAcrossFineGrid(w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5)), btScalar(0.5), w,
	                                            btVector3(1, 0, 0), false));
}

TEST(MeshContactScenario, BoxSlidingDiagonallyAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	expectSlidesUndisturbed(slideAcrossFineGrid(w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5)), btScalar(0.5), w,
	                                            btVector3(1, 0, btScalar(0.3)), false));
}

TEST(MeshContactScenario, SphereSlidingAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	expectSlidesUndisturbed(
	    slideAcrossFineGrid(w.shape<btSphereShape>(btScalar(0.5)), btScalar(0.5), w, btVector3(1, 0, 0), false));
}

TEST(MeshContactScenario, CapsuleSlidingSidewaysAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	// Lying along z, sliding along x: its core crosses the grid's edges all along its length.
	expectSlidesUndisturbed(slideAcrossFineGrid(w.shape<btCapsuleShapeZ>(btScalar(0.25), btScalar(1)), btScalar(0.25),
	                                            w, btVector3(1, 0, 0), false));
}

TEST(MeshContactScenario, HullBoxSlidingAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	btConvexHullShape* hull = hullBox(w, btVector3(0.5, 0.5, 0.5));
	expectSlidesUndisturbed(slideAcrossFineGrid(hull, btScalar(0.5) + hull->getMargin(), w, btVector3(1, 0, 0), false));
}

TEST(MeshContactScenario, HullBoxSlidingDiagonallyAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	btConvexHullShape* hull = hullBox(w, btVector3(0.5, 0.5, 0.5));
	expectSlidesUndisturbed(
	    slideAcrossFineGrid(hull, btScalar(0.5) + hull->getMargin(), w, btVector3(1, 0, btScalar(0.3)), false));
}

// Rolling (friction 1): the sphere's closest points on the triangles beside the one it is over are
// edges a few centimetres away, whose normals lean by a couple of degrees; taken for face points (their
// normals are within the face tolerance) they threw it up by 1.1 cm.
TEST(MeshContactScenario, SphereRollingAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	expectSlidesUndisturbed(slideAcrossFineGrid(w.shape<btSphereShape>(btScalar(0.5)), btScalar(0.5), w,
	                                            btVector3(1, 0, btScalar(0.3)), true));
}

TEST(MeshContactScenario, SphereRollingStraightAcrossAFineMeshAt10MetresPerSecondKeepsItsSpeed)
{
	TestWorld w;
	expectSlidesUndisturbed(
	    slideAcrossFineGrid(w.shape<btSphereShape>(btScalar(0.5)), btScalar(0.5), w, btVector3(1, 0, 0), true));
}
