// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ConvexDecompositionScene.h"

#include <stdio.h>

#include <chrono>

namespace convex_decomposition_demo
{
bool decompose(const char* name, const caliber::ExampleMesh& mesh, Decomposed& out)
{
	caliber::ConvexDecompositionParameters parameters;
	parameters.maxHulls = 32;
	parameters.concavityTolerance = 0.05;
	out.name = name;
	const auto start = std::chrono::steady_clock::now();
	const bool ok = caliber::decomposeConvex(&mesh.vertices[0], mesh.vertices.size(), &mesh.indices[0],
	                                         mesh.indices.size(), parameters, out.result);
	out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
	if (!ok)
	{
		printf("%-8s: %s\n", name, out.result.error.c_str());
		return false;
	}
	printf(
	    "%-8s: %4d triangles -> %2zu hulls, mesh volume %.5f m^3, hulls %.5f m^3, volume error %5.2f %% (%s), %.1f "
	    "ms\n",
	    name, mesh.indices.size() / 3, out.result.hulls.size(), out.result.meshVolume, out.result.hullVolume,
	    100 * out.result.volumeError(), out.result.withinTolerance ? "within 5 %" : "NOT within 5 %", out.milliseconds);
	out.shape = caliber::buildDecompositionShape(out.result);
	btAlignedObjectArray<btScalar> masses;
	for (const auto& hull : out.result.hulls) masses.push_back(btScalar(hull.meshVolume / out.result.meshVolume));
	out.shape.compound->calculatePrincipalAxisTransform(&masses[0], out.principal, out.inertia);
	out.centred.reset(new btCompoundShape());
	for (int i = 0; i < out.shape.compound->getNumChildShapes(); ++i)
		out.centred->addChildShape(out.principal.inverse() * out.shape.compound->getChildTransform(i),
		                           out.shape.compound->getChildShape(i));
	return true;
}

Scene::Scene(Decomposed& torus, Decomposed& cup, Decomposed& bracket)
{
	world().setGravity(btVector3(0, 0, btScalar(-9.81)));
	m_ground.reset(new btRigidBody(0, nullptr, &m_groundShape));
	world().addRigidBody(m_ground.get());

	// The torus and the bracket fall from 0.5 m, tilted; the cup stands upright at x = 0 with a ball above it.
	const auto add = [&](Decomposed& d, const btVector3& at, const btQuaternion& tilt)
	{
		btTransform pose(tilt, at);
		m_bodies.emplace_back(new btRigidBody(1, nullptr, d.centred.get(), d.inertia));
		m_bodies.back()->setWorldTransform(pose * d.principal);
		m_bodies.back()->setFriction(btScalar(0.8));
		world().addRigidBody(m_bodies.back().get());
	};
	add(torus, btVector3(-1.2, 0, btScalar(0.5)), btQuaternion(btVector3(1, 0, 0), btScalar(0.3)));
	add(cup, btVector3(0, 0, btScalar(0.001)), btQuaternion::getIdentity());
	add(bracket, btVector3(1.2, 0, btScalar(0.5)), btQuaternion(btVector3(0, 1, 0), btScalar(0.2)));
	btVector3 ballInertia;
	m_ballShape.calculateLocalInertia(btScalar(0.1), ballInertia);
	m_ball.reset(new btRigidBody(btScalar(0.1), nullptr, &m_ballShape, ballInertia));
	m_ball->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.02), btScalar(0.8))));
	m_ball->setRollingFriction(btScalar(0.02));
	world().addRigidBody(m_ball.get());
}

Scene::~Scene()
{
	for (const auto& body : m_bodies) world().removeRigidBody(body.get());
	world().removeRigidBody(m_ball.get());
	world().removeRigidBody(m_ground.get());
}
}  // namespace convex_decomposition_demo
