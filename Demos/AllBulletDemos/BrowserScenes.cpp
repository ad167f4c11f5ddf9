// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BrowserScenes.h"

#include "CcdScene.h"
#include "CharacterScene.h"
#include "ConcaveScene.h"
#include "ConstraintScene.h"
#include "ForkLiftScene.h"
#include "Ragdoll.h"
#include "SoftScenes.h"
#include "DemoPictures.h"
#include "DemoWorld.h"
#include "DemoPrograms.h"
#include "HelloWorldScene.h"
#include "VehicleScene.h"
#include "WorldScene.h"
#ifdef CALIBER_BROWSER_BSP
#include "BspLoader/BspConverter.h"
#include "BspLoader/BspLoader.h"
#include "BspScene.h"
#endif
#ifdef CALIBER_BROWSER_OBJ
#include "ObjLoader/MeshShapes.h"
#include "ObjLoader/ObjLoader.h"
#include "ObjScene.h"
#endif
#ifdef CALIBER_BROWSER_DECOMPOSITION
#include "ConvexDecompositionScene.h"
#endif
#ifdef CALIBER_BROWSER_COLLADA
#include "ColladaScene.h"
#endif

namespace all_bullet_demos
{
namespace
{
// BasicDemo's scene (Demos/BasicDemo): a 5 x 5 x 5 block of unit boxes, 0.2 apart, over a static ground.
class BasicScene : public benchmark_demo::Scene
{
public:
	BasicScene()
	{
		world().setGravity(btVector3(0, -10, 0));
		addBody(own(new btBoxShape(btVector3(50, 50, 50))), 0,
		        btTransform(btQuaternion::getIdentity(), btVector3(0, -50, 0)));
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		for (int k = 0; k < 5; ++k)
			for (int i = 0; i < 5; ++i)
				for (int j = 0; j < 5; ++j)
					addBody(box, 1,
					        btTransform(btQuaternion::getIdentity(),
					                    btVector3(btScalar(2.2) * (i - 2), btScalar(1.5) + btScalar(2.2) * k,
					                              btScalar(2.2) * (j - 2))));
	}
	bool report(std::string& line, int) const override
	{
		line = "browser scene";
		return true;
	}
};

// RagdollDemo's scene (Demos/RagdollDemo): six ragdolls dropped from 1 to 6 m, each tipped a little
// differently, over a static ground.
class RagdollScene : public benchmark_demo::Scene, public ragdoll::Owner
{
public:
	RagdollScene()
	{
		world().setGravity(btVector3(0, -10, 0));
		addBody(own(new btBoxShape(btVector3(50, 1, 50))), 0,
		        btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
		m_ragdolls.resize(6);
		for (int i = 0; i < 6; ++i)
		{
			ragdoll::build(*this, btVector3(btScalar(-5 + 2 * i), btScalar(1 + i), 0), 1, m_ragdolls[size_t(i)]);
			m_ragdolls[size_t(i)].bodies[0]->applyCentralImpulse(
			    btVector3(btScalar(0.5 * (i % 3)), 0, btScalar(0.3 * (i % 2))));
		}
	}
	btCollisionShape* keepShape(btCollisionShape* shape) override { return own(shape); }
	btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btTransform& pose) override
	{
		return Scene::addBody(shape, mass, pose);
	}
	void addJoint(btTypedConstraint* joint) override { Scene::addJoint(joint); }
	bool report(std::string& line, int) const override
	{
		line = "browser scene";
		return true;
	}

private:
	std::vector<ragdoll::Ragdoll> m_ragdolls;
};

// A benchmark_demo::Scene as a browser demo.
class SceneDemo : public BrowserDemo
{
public:
	explicit SceneDemo(std::unique_ptr<benchmark_demo::Scene> scene) : m_scene(std::move(scene)) {}
	btDiscreteDynamicsWorld& world() override { return m_scene->world(); }
	void step() override
	{
		m_scene->world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		m_scene->afterStep();
	}

private:
	std::unique_ptr<benchmark_demo::Scene> m_scene;
};

// ConstraintDemo's joints, stepped as the demo steps them (the door's torque flips every second).
class ConstraintDemo : public BrowserDemo
{
public:
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.step(++m_frame); }
	// The row of joints from the front, as ConstraintDemo's picture shows it (the welded L falls away).
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(btScalar(-0.5), btScalar(3.8), btScalar(-0.5));
		focusMax = btVector3(btScalar(26.5), btScalar(6.2), btScalar(0.5));
		viewDirection = btVector3(0, btScalar(-0.15), -1);
		return true;
	}

private:
	constraint_demo::Scene m_scene;
	int m_frame = 0;
};

// CcdPhysicsDemo's third run: fast spheres stopped by a 1 cm wall with swept CCD.
class CcdDemo : public BrowserDemo
{
public:
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.)); }
	// The spheres' start and the wall, from the side (the spheres are fired along +x).
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(-6, -5, -1);
		focusMax = btVector3(1, 6, 2);
		viewDirection = btVector3(btScalar(0.3), btScalar(-0.3), -1);
		return true;
	}

private:
	ccd_demo::Scene m_scene{ccd_demo::kSweptCcd};
};

// ConcaveDemo's height-field run: spheres, boxes and capsules dropped on rolling terrain.
class ConcaveDemo : public BrowserDemo
{
public:
	ConcaveDemo() { m_scene.build(concave_demo::kHeightField); }
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.)); }

private:
	concave_demo::Scene m_scene;
};

// VehicleDemo's car on its terrain, driven by the arrows (Enter brakes).
class VehicleDemo : public BrowserDemo
{
public:
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.)); }
	bool driven() const override { return true; }
	void control(const Controls& c) override { m_scene.drive(btScalar(c.forward), btScalar(c.turn), c.brake); }
	btVector3 driverPosition() override { return m_scene.chassis().getCenterOfMassPosition(); }
	void decorate(caliber::demo::Scene& scene) override
	{
		caliber::demo::addVehicleWheels(scene, m_scene.car(), vehicle_demo::kWheelWidth);
	}
	// The car and the bumps ahead of it, from behind.
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(-4, 0, -54);
		focusMax = btVector3(4, 3, -40);
		viewDirection = btVector3(btScalar(0.3), btScalar(-0.4), 1);
		return true;
	}

private:
	vehicle_demo::Scene m_scene;
};

// CharacterDemo's course, walked by the arrows (Enter jumps).
class CharacterDemo : public BrowserDemo
{
public:
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.world().stepSimulation(character_demo::kStep, 1, character_demo::kStep); }
	bool driven() const override { return true; }
	void control(const Controls& c) override { m_scene.walk(btScalar(c.forward), btScalar(c.turn), c.brake); }
	btVector3 driverPosition() override { return m_scene.feet(); }
	// The first lanes ahead of the character, from behind it.
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(-2, 0, -2);
		focusMax = btVector3(12, 2, 8);
		viewDirection = btVector3(btScalar(0.4), btScalar(-0.5), 1);
		return true;
	}

private:
	character_demo::Scene m_scene;
};

// ForkLiftDemo's fork lift and load, driven by the arrows (Enter brakes), U / D raise and lower the fork.
class ForkLiftDemo : public BrowserDemo
{
public:
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.)); }
	bool driven() const override { return true; }
	void control(const Controls& c) override
	{
		m_scene.drive(btScalar(c.forward), btScalar(c.turn), btScalar(c.lift), c.brake);
	}
	btVector3 driverPosition() override { return m_scene.chassis()->getCenterOfMassPosition(); }
	void decorate(caliber::demo::Scene& scene) override
	{
		caliber::demo::addVehicleWheels(scene, m_scene.vehicle(), fork_lift_demo::kWheelWidth);
	}
	// The fork lift and the load ahead of it, from behind and to the side.
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(-2, 0, -3);
		focusMax = btVector3(2, 3, 11);
		viewDirection = btVector3(btScalar(0.5), btScalar(-0.4), 1);
		return true;
	}

private:
	fork_lift_demo::Scene m_scene;
};

// One of SoftDemo's scenes (cloth, balls, ropes, attachments, friction, impact).
class SoftDemo : public BrowserDemo
{
public:
	explicit SoftDemo(const std::string& scene) { soft_demo::buildScene(m_scene, scene); }
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.step(1); }

private:
	soft_demo::Scene m_scene;
};

// An empty world (gravity -y) for demos that draw without one: it holds only the boxes the user shoots.
class EmptyWorld
{
public:
	EmptyWorld() { world().setGravity(btVector3(0, -10, 0)); }
	btDiscreteDynamicsWorld& world() { return m_physics.world(); }

private:
	caliber::demo::DemoWorld m_physics;
};

// HelloWorld's ball dropped on the ground, stepped as HelloWorld steps it.
class HelloWorldDemo : public BrowserDemo
{
public:
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }
	void step() override { m_scene.world().stepSimulation(btScalar(1. / 60.), 10); }
	// The ball's whole fall and the ground under it.
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(-3, 0, -3);
		focusMax = btVector3(3, 11, 3);
		viewDirection = btVector3(btScalar(-0.55), btScalar(-0.45), -1);
		return true;
	}

private:
	hello_world::Scene m_scene;
};

// An Extras demo whose library or file is missing here: an empty world and a notice that says why.
class MissingDemo : public BrowserDemo
{
public:
	MissingDemo(const std::string& name, const std::string& why) : m_notice(name + " IS SKIPPED: " + why)
	{
		std::fprintf(stderr, "AllBulletDemos: %s is skipped: %s\n", name.c_str(), why.c_str());
	}
	btDiscreteDynamicsWorld& world() override { return m_empty.world(); }
	void step() override { m_empty.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.)); }
	std::string notice() const override { return m_notice; }
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		focusMin = btVector3(-1, -1, -1);
		focusMax = btVector3(1, 1, 1);
		viewDirection = btVector3(btScalar(-0.55), btScalar(-0.45), -1);
		return true;
	}

private:
	EmptyWorld m_empty;
	std::string m_notice;
};

// A demo that loads something and steps at 60 Hz; its own view (the z-up demos look down at a slant).
class LoadedDemo : public BrowserDemo
{
public:
	void step() override { world().stepSimulation(btScalar(1. / 60.), 0); }
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		if (!m_viewGiven) return false;
		focusMin = m_focusMin;
		focusMax = m_focusMax;
		viewDirection = m_viewDirection;
		return true;
	}

protected:
	void setView(const btVector3& focusMin, const btVector3& focusMax, const btVector3& viewDirection)
	{
		m_focusMin = focusMin;
		m_focusMax = focusMax;
		m_viewDirection = viewDirection;
		m_viewGiven = true;
	}

private:
	btVector3 m_focusMin{0, 0, 0}, m_focusMax{0, 0, 0}, m_viewDirection{0, 0, -1};
	bool m_viewGiven = false;
};

#ifdef CALIBER_BROWSER_BSP
// BspDemo's example room (written at build time) with its 44 bodies.
class BspDemo : public LoadedDemo
{
public:
	explicit BspDemo(caliber::BspLevelShape level) : m_level(std::move(level)), m_scene(m_level.compound.get())
	{
		// The room from above at a slant, as BspDemo's picture (z up).
		setView(btVector3(-8, -8, 0), btVector3(8, 8, 6), btVector3(btScalar(0.3), btScalar(0.8), btScalar(-1)));
	}
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }

private:
	caliber::BspLevelShape m_level;
	bsp_demo::Scene m_scene;
};

std::unique_ptr<BrowserDemo> makeBspDemo()
{
	caliber::BspLevel level;
	if (!caliber::loadBspFile(CALIBER_EXAMPLE_BSP, level))
		return std::unique_ptr<BrowserDemo>(new MissingDemo("BspDemo", level.error));
	caliber::BspLevelShape shape = caliber::buildBspLevelShape(caliber::convertBspBrushes(level, bsp_demo::kScale));
	if (!shape.compound)
		return std::unique_ptr<BrowserDemo>(new MissingDemo("BspDemo", "the level has no solid brush"));
	return std::unique_ptr<BrowserDemo>(new BspDemo(std::move(shape)));
}
#endif

#ifdef CALIBER_BROWSER_OBJ
// ObjDemo's built-in bowl and pieces.
class ObjDemo : public LoadedDemo
{
public:
	ObjDemo(caliber::StaticMeshShape level, std::vector<std::unique_ptr<btConvexHullShape>> hulls)
	    : m_level(std::move(level)), m_hulls(std::move(hulls)), m_scene(m_level.shape.get(), m_hulls)
	{
	}
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }

private:
	caliber::StaticMeshShape m_level;
	std::vector<std::unique_ptr<btConvexHullShape>> m_hulls;
	obj_demo::Scene m_scene;
};

std::unique_ptr<BrowserDemo> makeObjDemo()
{
	caliber::ObjModel level, pieces;
	const std::string levelText = obj_demo::levelText(), piecesText = obj_demo::piecesText();
	if (!caliber::loadObjFromMemory(levelText.data(), levelText.size(), level) ||
	    !caliber::loadObjFromMemory(piecesText.data(), piecesText.size(), pieces))
		return std::unique_ptr<BrowserDemo>(new MissingDemo("ObjDemo", "the built-in models do not load"));
	caliber::StaticMeshShape levelShape = caliber::buildStaticMeshShape(level);
	std::vector<std::unique_ptr<btConvexHullShape>> hulls = caliber::buildConvexHullShapes(pieces);
	if (!levelShape.shape || hulls.empty())
		return std::unique_ptr<BrowserDemo>(new MissingDemo("ObjDemo", "the models gave no shapes"));
	return std::unique_ptr<BrowserDemo>(new ObjDemo(std::move(levelShape), std::move(hulls)));
}
#endif

#ifdef CALIBER_BROWSER_DECOMPOSITION
// ConvexDecompositionDemo's torus, cup (with its ball) and bracket, decomposed as the demo does (it
// prints the decompositions).
class ConvexDecompositionDemo : public LoadedDemo
{
public:
	ConvexDecompositionDemo() = default;
	bool build()
	{
		using convex_decomposition_demo::decompose;
		const bool ok =
		    decompose("torus", caliber::makeTorusMesh(btScalar(0.4), btScalar(0.12), 24, 12), m_torus) &&
		    decompose("cup", caliber::makeCupMesh(btScalar(0.3), btScalar(0.04), btScalar(0.4), btScalar(0.05), 24),
		              m_cup) &&
		    decompose("bracket", caliber::makeLBracketMesh(btScalar(0.6), btScalar(0.15), btScalar(0.15)), m_bracket);
		if (!ok) return false;
		m_scene.reset(new convex_decomposition_demo::Scene(m_torus, m_cup, m_bracket));
		setView(btVector3(-2, -1, 0), btVector3(2, 1, 1), btVector3(btScalar(0.3), btScalar(0.8), btScalar(-1)));
		return true;
	}
	btDiscreteDynamicsWorld& world() override { return m_scene->world(); }

private:
	convex_decomposition_demo::Decomposed m_torus, m_cup, m_bracket;
	std::unique_ptr<convex_decomposition_demo::Scene> m_scene;
};
#endif

#ifdef CALIBER_BROWSER_COLLADA
// ColladaDemo's playground document, stepped at 60 Hz.
class ColladaDemo : public LoadedDemo
{
public:
	bool load() { return m_scene.load(CALIBER_COLLADA_DEMO_SCENE); }
	std::string error() { return m_scene.document().error; }
	btDiscreteDynamicsWorld& world() override { return m_scene.world(); }

private:
	collada_demo::Scene m_scene;
};
#endif

std::unique_ptr<BrowserDemo> makeExtrasDemo(const std::string& name)
{
	if (name == "BspDemo")
	{
#ifdef CALIBER_BROWSER_BSP
		return makeBspDemo();
#else
		return std::unique_ptr<BrowserDemo>(
		    new MissingDemo(name, "this build has no BspLoader (CALIBER_BUILD_EXTRAS)"));
#endif
	}
	if (name == "ObjDemo")
	{
#ifdef CALIBER_BROWSER_OBJ
		return makeObjDemo();
#else
		return std::unique_ptr<BrowserDemo>(
		    new MissingDemo(name, "this build has no ObjLoader (CALIBER_BUILD_EXTRAS)"));
#endif
	}
	if (name == "ConvexDecompositionDemo")
	{
#ifdef CALIBER_BROWSER_DECOMPOSITION
		std::unique_ptr<ConvexDecompositionDemo> demo(new ConvexDecompositionDemo());
		if (demo->build()) return std::unique_ptr<BrowserDemo>(demo.release());
		return std::unique_ptr<BrowserDemo>(new MissingDemo(name, "a decomposition failed (see the terminal)"));
#else
		return std::unique_ptr<BrowserDemo>(
		    new MissingDemo(name, "this build has no ConvexDecomposition (CALIBER_BUILD_EXTRAS)"));
#endif
	}
	if (name == "ColladaDemo")
	{
#ifdef CALIBER_BROWSER_COLLADA
		std::unique_ptr<ColladaDemo> demo(new ColladaDemo());
		if (demo->load()) return std::unique_ptr<BrowserDemo>(demo.release());
		return std::unique_ptr<BrowserDemo>(new MissingDemo(name, demo->error()));
#else
		return std::unique_ptr<BrowserDemo>(
		    new MissingDemo(name, "it needs tinyxml2 (Debian libtinyxml2-dev), which this build did not find"));
#endif
	}
	return nullptr;
}

const char* const kExtrasDemos[] = {"BspDemo", "ObjDemo", "ConvexDecompositionDemo", "ColladaDemo"};

// A demo without a world to step: its program runs once with a SceneRecording set (its report goes to
// the terminal), and the browser plays back what it drew, one shot every half second, holding the last.
class RecordedDemo : public BrowserDemo
{
public:
	RecordedDemo(const std::string& name, int (*program)(int, char**)) : m_name(name)
	{
		std::printf("AllBulletDemos: %s's program runs; its report:\n", name.c_str());
		std::vector<char> argument(name.begin(), name.end());
		argument.push_back('\0');
		char* argv[] = {argument.data(), nullptr};
		caliber::demo::setSceneRecording(&m_recording);
		m_exitCode = program(1, argv);
		caliber::demo::setSceneRecording(nullptr);
		std::fflush(stdout);
	}
	btDiscreteDynamicsWorld& world() override { return m_empty.world(); }
	void step() override
	{
		m_empty.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		++m_steps;
	}
	void decorate(caliber::demo::Scene& scene) override
	{
		if (!m_recording.shots.empty()) scene.append(m_recording.shots[size_t(shot())].scene);
	}
	bool startView(btVector3& focusMin, btVector3& focusMax, btVector3& viewDirection) const override
	{
		if (m_recording.shots.empty()) return false;
		// Every shot's focus: the camera does not have to move during the replay.
		focusMin = m_recording.shots[0].focusMin;
		focusMax = m_recording.shots[0].focusMax;
		for (const caliber::demo::SceneRecording::Shot& s : m_recording.shots)
		{
			focusMin.setMin(s.focusMin);
			focusMax.setMax(s.focusMax);
		}
		viewDirection = m_recording.shots.back().viewDirection;
		return true;
	}
	std::string notice() const override
	{
		char line[160];
		std::snprintf(line, sizeof(line), "%s'S PROGRAM: %s; ITS DRAWING, SHOT %d OF %d (REPORT IN THE TERMINAL)",
		              m_name.c_str(), m_exitCode == 0 ? "CHECKS PASSED" : "A CHECK FAILED", shot() + 1,
		              int(m_recording.shots.size()));
		return line;
	}

private:
	int shot() const
	{
		const int shots = int(m_recording.shots.size());
		return shots == 0 ? 0 : btMin(shots - 1, m_steps / kStepsPerShot);
	}
	static const int kStepsPerShot = 30;
	std::string m_name;
	EmptyWorld m_empty;
	caliber::demo::SceneRecording m_recording;
	int m_exitCode = 0;
	int m_steps = 0;
};

struct RecordedProgram
{
	const char* name;
	int (*program)(int, char**);
};
const RecordedProgram kRecordedPrograms[] = {
    {"LinearMathDemo", caliber::demo::linearMathDemo},
    {"SimplexDemo", caliber::demo::simplexDemo},
    {"GjkConvexCastDemo", caliber::demo::gjkConvexCastDemo},
    {"CollisionInterfaceDemo", caliber::demo::collisionInterfaceDemo},
    {"Raytracer", caliber::demo::raytracerDemo},
    {"UserCollisionAlgorithm", caliber::demo::userCollisionAlgorithmDemo},
};
}  // namespace

std::vector<std::string> demoNames()
{
	std::vector<std::string> names;
	for (const RecordedProgram& program : kRecordedPrograms) names.push_back(program.name);
	names.push_back("HelloWorld");
	const std::vector<std::string> stepped = {"BasicDemo",   "RagdollDemo", "ConstraintDemo", "CcdPhysicsDemo",
	                                          "ConcaveDemo", "VehicleDemo", "CharacterDemo",  "ForkLiftDemo"};
	names.insert(names.end(), stepped.begin(), stepped.end());
	for (const char* name : kExtrasDemos) names.push_back(name);
	for (const std::string& name : soft_demo::sceneNames()) names.push_back("SoftDemo/" + name);
	for (const std::string& name : benchmark_demo::sceneNames()) names.push_back("Benchmark/" + name);
	return names;
}

std::unique_ptr<BrowserDemo> makeDemo(const std::string& name)
{
	for (const RecordedProgram& program : kRecordedPrograms)
		if (name == program.name) return std::unique_ptr<BrowserDemo>(new RecordedDemo(name, program.program));
	if (name == "HelloWorld") return std::unique_ptr<BrowserDemo>(new HelloWorldDemo());
	for (const char* extras : kExtrasDemos)
		if (name == extras) return makeExtrasDemo(name);
	std::unique_ptr<benchmark_demo::Scene> scene;
	if (name == "BasicDemo") scene.reset(new BasicScene());
	if (name == "RagdollDemo") scene.reset(new RagdollScene());
	if (name == "ConstraintDemo") return std::unique_ptr<BrowserDemo>(new ConstraintDemo());
	if (name == "CcdPhysicsDemo") return std::unique_ptr<BrowserDemo>(new CcdDemo());
	if (name == "ConcaveDemo") return std::unique_ptr<BrowserDemo>(new ConcaveDemo());
	if (name == "VehicleDemo") return std::unique_ptr<BrowserDemo>(new VehicleDemo());
	if (name == "CharacterDemo") return std::unique_ptr<BrowserDemo>(new CharacterDemo());
	if (name == "ForkLiftDemo") return std::unique_ptr<BrowserDemo>(new ForkLiftDemo());
	const std::string soft = "SoftDemo/";
	if (name.compare(0, soft.size(), soft) == 0)
	{
		const std::vector<std::string> names = soft_demo::sceneNames();
		for (const std::string& known : names)
			if (name.substr(soft.size()) == known) return std::unique_ptr<BrowserDemo>(new SoftDemo(known));
		return nullptr;
	}
	const std::string prefix = "Benchmark/";
	if (name.compare(0, prefix.size(), prefix) == 0) scene = benchmark_demo::makeScene(name.substr(prefix.size()));
	return scene ? std::unique_ptr<BrowserDemo>(new SceneDemo(std::move(scene))) : nullptr;
}
}  // namespace all_bullet_demos
