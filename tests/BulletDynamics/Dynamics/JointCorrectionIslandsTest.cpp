// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// With a task scheduler of more than one thread, the joint position correction runs island by island on
// the threads (src/BulletDynamics/Dynamics/btJointCorrectionIslands.cpp): every articulation's tree
// solve and Gauss-Seidel sweep, with the serial pass's global choices (another iteration, the trees'
// shortened step) made on the calling thread. The world must end with the bits of the pass without a
// scheduler, at any thread count and with a scheduler that splits loops unevenly.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "DynamicsWorldTestUtil.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
// 12 small "ragdolls" (a torso and 10 boxes on ball, hinge and cone-twist joints, too short for the exact
// tree solve), two long chains of 20 links (ball joints and hinges: the exact tree solve), and a chain of
// 14 links whose middle link turns about one axis only (the tree leaves its joints to the sweep), all hung
// sideways from one static ceiling body, so that they swing and every articulation's correction has
// work; each articulation is its own island.
struct Articulations
{
	Articulations()
	{
		box = scene.shape<btBoxShape>(btVector3(btScalar(0.1), btScalar(0.1), btScalar(0.1)));
		// The ceiling: one static body that every articulation hangs from.
		ceiling = addBody(0, btVector3(0, 20, 0));
		// Ragdolls between the long chains, so that the chains fall into different chunks of islands (whose
		// steps must still be shortened alike, by the largest turn of both).
		addChain(btVector3(0, 15, 5), 20, false, -1);
		for (int doll = 0; doll < 6; ++doll) addRagdoll(btVector3(btScalar(doll) * 3, 12, 0));
		addChain(btVector3(0, 15, 8), 20, true, -1);
		for (int doll = 6; doll < 12; ++doll) addRagdoll(btVector3(btScalar(doll) * 3, 12, 0));
		addChain(btVector3(0, 15, 11), 14, false, 7);
	}

	btRigidBody* addBody(btScalar mass, const btVector3& at)
	{
		// The articulations' links overlap their neighbours: collisions between them are not the point.
		btRigidBody* body = scene.addFilteredBody(box, mass, at, 1, 0);
		if (mass > 0) body->setActivationState(DISABLE_DEACTIVATION);
		return body;
	}
	template <class Joint, class... Args>
	void addJoint(Args&&... args)
	{
		joints.push_back(scene.addJoint<Joint>(true, std::forward<Args>(args)...));
	}
	// A torso with two arms of three boxes and two legs of two, 10 joints, hung from the ceiling.
	void addRagdoll(const btVector3& at)
	{
		btRigidBody* torso = addBody(2, at);
		addJoint<btPoint2PointConstraint>(
		    *ceiling, *torso, at + btVector3(0, 1, 0) - ceiling->getCenterOfMassPosition(), btVector3(0, 1, 0));
		const btVector3 directions[4] = {btVector3(1, 0, 0), btVector3(-1, 0, 0), btVector3(btScalar(0.5), -1, 0),
		                                 btVector3(btScalar(-0.5), -1, 0)};
		for (int limb = 0; limb < 4; ++limb)
		{
			btRigidBody* previous = torso;
			const int links = limb < 2 ? 3 : 2;
			for (int link = 0; link < links; ++link)
			{
				const btVector3 step = directions[limb] * btScalar(0.3);
				btRigidBody* body = addBody(1, previous->getCenterOfMassPosition() + step);
				const btVector3 pivotInPrevious = step * btScalar(0.5);
				const btVector3 pivotInBody = -step * btScalar(0.5);
				if (link == 0)
				{
					btTransform frameA, frameB;
					frameA.setIdentity();
					frameB.setIdentity();
					frameA.setOrigin(pivotInPrevious);
					frameB.setOrigin(pivotInBody);
					btConeTwistConstraint* shoulder =
					    scene.addJoint<btConeTwistConstraint>(true, *previous, *body, frameA, frameB);
					shoulder->setLimit(btScalar(0.8), btScalar(0.8), btScalar(0.5));
					joints.push_back(shoulder);
				}
				else if (link == 1)
				{
					addJoint<btHingeConstraint>(*previous, *body, pivotInPrevious, pivotInBody, btVector3(0, 0, 1),
					                            btVector3(0, 0, 1));
				}
				else
				{
					addJoint<btPoint2PointConstraint>(*previous, *body, pivotInPrevious, pivotInBody);
				}
				previous = body;
			}
		}
	}
	// A chain laid out sideways from the ceiling; hinged or on ball joints; the link numbered oddLink (if
	// any) turns about y only.
	void addChain(const btVector3& at, int links, bool hinged, int oddLink)
	{
		btRigidBody* previous = ceiling;
		btVector3 previousPivot = at - ceiling->getCenterOfMassPosition();
		for (int link = 0; link < links; ++link)
		{
			btRigidBody* body = addBody(1, at + btVector3(btScalar(link) * btScalar(0.3) + btScalar(0.15), 0, 0));
			if (link == oddLink) body->setAngularFactor(btVector3(0, 1, 0));
			const btVector3 pivotInBody(btScalar(-0.15), 0, 0);
			if (hinged)
				addJoint<btHingeConstraint>(*previous, *body, previousPivot, pivotInBody, btVector3(0, 0, 1),
				                            btVector3(0, 0, 1));
			else
				addJoint<btPoint2PointConstraint>(*previous, *body, previousPivot, pivotInBody);
			previous = body;
			previousPivot = btVector3(btScalar(0.15), 0, 0);
		}
	}
	// The largest gap between the pivots of the ball joints of the two long chains' kind (every
	// btPoint2PointConstraint).
	btScalar largestBallJointGap() const
	{
		btScalar largest = 0;
		for (const btTypedConstraint* joint : joints)
		{
			const btPoint2PointConstraint* ball = dynamic_cast<const btPoint2PointConstraint*>(joint);
			if (!ball) continue;
			const btVector3 a = ball->getRigidBodyA().getWorldTransform() * ball->getPivotInA();
			const btVector3 b = ball->getRigidBodyB().getWorldTransform() * ball->getPivotInB();
			largest = btMax(largest, (a - b).length());
		}
		return largest;
	}
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(scene.bodies()); }

	caliber_test::TestWorld scene;
	btBoxShape* box = nullptr;
	btRigidBody* ceiling = nullptr;
	std::vector<btTypedConstraint*> joints;
};

const int kSteps = 60;

std::vector<btScalar> stepAndRead(btScalar* gap = nullptr)
{
	Articulations articulations;
	for (int i = 0; i < kSteps; ++i) articulations.scene.world()->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	if (gap) *gap = articulations.largestBallJointGap();
	return articulations.state();
}

std::vector<btScalar> run(int threads, btScalar* gap = nullptr)
{
	caliber_test::ScopedTaskScheduler scheduler(threads);
	return stepAndRead(gap);
}

// The uneven-splitting scheduler of TestThreadsUtil.h, noting whether the island-by-island correction's
// loop was among the loops it ran.
class UnevenSplitScheduler : public caliber_test::UnevenSplitScheduler
{
public:
	void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) override
	{
		if (std::string(typeid(body).name()).find("ChunkStep") != std::string::npos) sawIslandCorrection = true;
		caliber_test::UnevenSplitScheduler::parallelFor(iBegin, iEnd, grainSize, body);
	}
	bool sawIslandCorrection = false;
};

bool sameBits(const std::vector<btScalar>& a, const std::vector<btScalar>& b)
{
	return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)) == 0;
}
}  // namespace

TEST(JointCorrectionIslands, ArticulationsEndWithTheSerialBitsAtOneTwoThreeFourAndEightThreads)
{
	btScalar gap = 1;
	const std::vector<btScalar> serial = run(0, &gap);
	// The correction holds the articulations together: after a second of swinging, the ball joints'
	// pivots within 1 cm (a 20-link chain released horizontally keeps its gaps within 4 mm,
	// docs/constraints.md; a step's worth of a 5 m/s swing, uncorrected, is 8 cm).
	EXPECT_LT(gap, btScalar(0.01));
	for (int threads : {1, 2, 3, 4, 8}) EXPECT_TRUE(sameBits(serial, run(threads))) << threads << " threads";
}

TEST(JointCorrectionIslands, AUserSchedulerThatSplitsLoopsUnevenlyGivesTheSerialBits)
{
	const std::vector<btScalar> serial = run(0);
	UnevenSplitScheduler uneven;
	btSetTaskScheduler(&uneven);
	const std::vector<btScalar> split = stepAndRead();
	btSetTaskScheduler(0);
	// The scheduler claims two threads, so the correction went island by island through it.
	EXPECT_TRUE(uneven.sawIslandCorrection);
	EXPECT_TRUE(sameBits(serial, split));
}

TEST(JointCorrectionIslands, ChangingTheThreadCountBetweenStepsKeepsTheSerialBits)
{
	const std::vector<btScalar> serial = run(0);
	std::vector<btScalar> mixed;
	{
		Articulations articulations;
		std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
		for (int i = 0; i < kSteps; ++i)
		{
			// Steps alternate between no scheduler and 2 or 3 threads, so the chunks' scratch kept from
			// step to step is reused after steps that did not touch it.
			const int threads = i % 3;
			btSetTaskScheduler(pool && threads > 0 ? pool.get() : 0);
			if (pool && threads > 0) pool->setNumThreads(threads + 1);
			articulations.scene.world()->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		}
		btSetTaskScheduler(0);
		mixed = articulations.state();
	}
	EXPECT_TRUE(sameBits(serial, mixed));
}
