// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// RagdollDemo: six ragdolls (11 capsules, 5 hinges and 5 cone-twist joints each) dropped onto the
// ground from different heights and tilts. Prints, every half second, how high they are and how far
// their joints have opened (pivot errors), and exits non-zero if a joint came apart. --png, --frames
// (default 300) and --png-sequence: docs/demos.md.

#include <cstdio>
#include <memory>
#include <vector>

#include "DemoPictures.h"
#include "DemoWorld.h"
#include "Ragdoll.h"

namespace
{
class World : public ragdoll::Owner
{
public:
	World()
	{
		world().setGravity(btVector3(0, -10, 0));
		btCollisionShape* ground = keepShape(new btBoxShape(btVector3(50, 1, 50)));
		btRigidBody::btRigidBodyConstructionInfo info(0, 0, ground);
		info.m_startWorldTransform.setOrigin(btVector3(0, -1, 0));
		m_bodies.emplace_back(new btRigidBody(info));
		world().addRigidBody(m_bodies.back().get());
	}
	~World()
	{
		for (auto& joint : m_joints) world().removeConstraint(joint.get());
		for (auto& body : m_bodies) world().removeRigidBody(body.get());
	}
	btCollisionShape* keepShape(btCollisionShape* shape) override
	{
		m_shapes.emplace_back(shape);
		return shape;
	}
	btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btTransform& pose) override
	{
		btVector3 inertia(0, 0, 0);
		shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, inertia);
		info.m_startWorldTransform = pose;
		m_bodies.emplace_back(new btRigidBody(info));
		world().addRigidBody(m_bodies.back().get());
		return m_bodies.back().get();
	}
	void addJoint(btTypedConstraint* joint) override
	{
		m_joints.emplace_back(joint);
		world().addConstraint(joint, true);
	}
	btDiscreteDynamicsWorld& world() { return m_physics.world(); }

private:
	caliber::demo::DemoWorld m_physics;  // the world, first in and last out
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
};
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "RagdollDemo";
	commandLine.defaultFrames = 300;
	commandLine.sequences = true;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	World w;
	std::vector<ragdoll::Ragdoll> ragdolls(6);
	for (int i = 0; i < 6; ++i)
	{
		ragdoll::build(w, btVector3(btScalar(-5 + 2 * i), btScalar(1 + i), 0), 1, ragdolls[i]);
		// Tip each one over a little, differently, so they land in different ways.
		ragdolls[i].bodies[0]->applyCentralImpulse(btVector3(btScalar(0.5 * (i % 3)), 0, btScalar(0.3 * (i % 2))));
	}
	std::printf("RagdollDemo: 6 ragdolls (66 capsules, 30 hinges, 30 cone-twist joints) falling onto the ground\n");
	std::printf("%6s %12s %12s %16s %16s\n", "time", "lowest y", "highest y", "max pivot err", "mean pivot err");
	btScalar worstEver = 0;
	for (int frame = 1; frame <= pictures.frames(); ++frame)
	{
		w.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		pictures.frame(w.world(), frame);
		btScalar lowest = BT_LARGE_FLOAT, highest = -BT_LARGE_FLOAT, worst = 0, sum = 0;
		for (const ragdoll::Ragdoll& r : ragdolls)
		{
			for (btRigidBody* body : r.bodies)
			{
				lowest = btMin(lowest, body->getCenterOfMassPosition().y());
				highest = btMax(highest, body->getCenterOfMassPosition().y());
			}
			for (int j = 0; j < ragdoll::Ragdoll::NUM_JOINTS; ++j)
			{
				const btScalar e = r.pivotError(j);
				worst = btMax(worst, e);
				sum += e;
			}
		}
		worstEver = btMax(worstEver, worst);
		if (frame % 30 == 0)
			std::printf("%5.1fs %12.3f %12.3f %14.5f m %14.6f m\n", frame / 60.0, double(lowest), double(highest),
			            double(worst), double(sum / (6 * ragdoll::Ragdoll::NUM_JOINTS)));
	}
	std::printf("worst pivot error over the run: %.5f m\n", double(worstEver));
	// A joint that opens by more than the pelvis's radius (0.15 m) has come apart.
	if (worstEver > btScalar(0.15))
	{
		std::printf("FAILED: a joint opened by more than 15 cm\n");
		return pictures.finish(1);
	}
	return pictures.finish(0);
}
