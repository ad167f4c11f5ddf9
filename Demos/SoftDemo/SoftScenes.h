// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_SOFT_SCENES_H
#define CALIBER_DEMOS_SOFT_SCENES_H
// SoftDemo's scenes (our own set-ups after Bullet's SoftDemo): Cloth, Pressure, Volume, Ropes,
// RopeAttach, ClothAttach, Sticks, Collide, Collide2, Collide3, Friction, Impact, Aero, Aero2, Torus,
// TorusMatch, Bunny, BunnyMatch, Cutting1, TetraCube and the cluster scenes ClusterDeform, ClusterCollide1,
// ClusterCollide2, ClusterSocket, ClusterHinge, ClusterCombine, ClusterCar, ClusterRobot, ClusterStackSoft,
// ClusterStackMixed (SoftScenes.cpp, SoftScenesMore.cpp), each built into a
// soft-rigid world with a 100 m ground (top face at y = 0). Used by SoftDemo, which runs and measures them, and by the
// demo browser.

#include <memory>
#include <string>
#include <vector>

#include "btBulletSoftBodyCommon.h"

namespace soft_demo
{
const btScalar kStep = btScalar(1. / 60.);

/// One scene's world: the parts, the ground, and ownership of what is added.
class Scene
{
public:
	Scene();
	virtual ~Scene();
	Scene(const Scene&) = delete;
	Scene& operator=(const Scene&) = delete;
	btSoftRigidDynamicsWorld& world() { return m_world; }
	btSoftBodyWorldInfo& info() { return m_world.getWorldInfo(); }
	/// True once a soft body was added.
	bool hasSoftBodies() const { return !m_softs.empty(); }
	btCollisionShape* own(btCollisionShape* shape);
	btRigidBody* addRigid(btScalar mass, const btVector3& position, btCollisionShape* shape);
	btRigidBody* addRigid(btScalar mass, const btTransform& pose, btCollisionShape* shape);
	btSoftBody* addSoft(btSoftBody* body);
	/// frames steps of 1/60 s.
	void step(int frames);

private:
	btSoftBodyRigidBodyCollisionConfiguration m_config;
	btCollisionDispatcher m_dispatcher{&m_config};
	btDbvtBroadphase m_broadphase;
	btSequentialImpulseConstraintSolver m_solver;
	btSoftRigidDynamicsWorld m_world{&m_dispatcher, &m_broadphase, &m_solver, &m_config};
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	std::vector<btSoftBody*> m_softs;
};

/// Bullet's SoftDemo motor for angular joints: turns towards goal by at most maxStep (rad/s) per solve.
struct Motor : btSoftBody::AJoint::IControl
{
	btScalar goal = 0, maxStep = 1;
	btScalar Speed(btSoftBody::AJoint*, btScalar current) override
	{
		return current + btMin(maxStep, btMax(-maxStep, goal - current));
	}
};

/// What each scene adds (the bodies SoftDemo measures).
struct Parts
{
	std::vector<btSoftBody*> softs;
	std::vector<btRigidBody*> rigids;
};

/// An 8 m cloth of 31 x 31 nodes pinned at two corners.
Parts buildCloth(Scene& scene);
/// A ball of gas (kPR = 1000) 3 m up.
Parts buildPressure(Scene& scene);
/// A hollow ball of soft links keeping its volume (kVC = 500) under three 2 kg boxes (rigids).
Parts buildVolume(Scene& scene);
/// 15 ropes of 2 to 9 m, fixed at one end, horizontal.
Parts buildRopes(Scene& scene);
/// A 3 m rope fixed at its top, a 2 kg box anchored to its end.
Parts buildRopeAttach(Scene& scene);
/// A cloth hanging from a 5 kg box (rigids[0]) at two corners.
Parts buildClothAttach(Scene& scene);
/// Three cloths on a 30 degree slope with kDF = 0.1, 0.5, 0.9 (the slope is not in rigids).
Parts buildFriction(Scene& scene);
/// A cloth stretched over four posts and a 1 kg box 3 m above it.
Parts buildImpact(Scene& scene);

/// A soft body (2 kg, 8 clusters with shape matching 0.5, soft links) dropped 3 m: it squashes and its
/// clusters bring its shape back.
Parts buildClusterDeform(Scene& scene);
/// Two cluster balls thrown at each other (CL_SS).
Parts buildClusterCollide1(Scene& scene);
/// Four cluster balls dropped on one another (CL_SS).
Parts buildClusterCollide2(Scene& scene);
/// A cluster ball held at a world point by a linear joint (a socket), pushed sideways.
Parts buildClusterSocket(Scene& scene);
/// A soft wheel on a static post (rigids[0]): a linear joint for the axle, an angular joint with a
/// motor (3 rad/s) about it.
Parts buildClusterHinge(Scene& scene);
/// A chain from a world point: two soft balls and a 1 kg box (rigids[0]) joined by linear joints.
Parts buildClusterCombine(Scene& scene);
/// Four flat soft discs (2.4 x 0.9 m, 6 clusters) stacked (CL_SS).
Parts buildClusterStackSoft(Scene& scene);
/// Soft disc, 1 kg box, soft disc, 1 kg box (rigids) stacked from the ground up.
Parts buildClusterStackMixed(Scene& scene);

/// 25 sticks (ropes with bending links) fixed at the ground, leaning over.
Parts buildSticks(Scene& scene);
/// Two gas balls (VF_SS) thrown at each other.
Parts buildCollide(Scene& scene);
/// Three soft volumes (kVC, VF_SS) falling on one another.
Parts buildCollide2(Scene& scene);
/// A free cloth (softs[1]) dropped onto a cloth pinned at its corners (softs[0]), VF_SS.
Parts buildCollide3(Scene& scene);
/// A flag hanging from two corners in a 10 m/s wind along +x.
Parts buildAero(Scene& scene);
/// Four free sheets falling through a 4 m/s wind along +z, with drag and lift on faces.
Parts buildAero2(Scene& scene);
/// A torus (our own procedural mesh) keeping its volume by kVC, dropped.
Parts buildTorus(Scene& scene);
/// The torus with soft links and pose matching (kMT).
Parts buildTorusMatch(Scene& scene);
/// A blob of gas (our own lumpy mesh standing in for Bullet's bunny), dropped.
Parts buildBunny(Scene& scene);
/// The blob with soft links and pose matching (kMT).
Parts buildBunnyMatch(Scene& scene);
/// A cloth hanging from its two top corners (SoftDemo cuts it with refine).
Parts buildCutting1(Scene& scene);
/// A 3 kg chassis (rigids[0]) on four soft cluster wheels driven by angular-joint motors.
Parts buildClusterCar(Scene& scene);
/// A rigid hub (rigids[0]) on three soft cluster feet, tumbling down a slope.
Parts buildClusterRobot(Scene& scene);
/// A cube of tetras (from TetGen text made here), dropped.
Parts buildTetraCube(Scene& scene);

/// The scenes' names, in SoftDemo's order.
std::vector<std::string> sceneNames();
/// Builds the named scene into scene; false for an unknown name.
bool buildScene(Scene& scene, const std::string& name);
}  // namespace soft_demo

#endif
