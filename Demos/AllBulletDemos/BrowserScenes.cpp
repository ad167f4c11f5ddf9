// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BrowserScenes.h"

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
}  // namespace

std::vector<std::string> demoNames()
{
	std::vector<std::string> names = {"BasicDemo"};
	for (const std::string& name : benchmark_demo::sceneNames()) names.push_back("Benchmark/" + name);
	return names;
}

std::unique_ptr<benchmark_demo::Scene> makeDemo(const std::string& name)
{
	if (name == "BasicDemo") return std::unique_ptr<benchmark_demo::Scene>(new BasicScene());
	const std::string prefix = "Benchmark/";
	if (name.compare(0, prefix.size(), prefix) == 0) return benchmark_demo::makeScene(name.substr(prefix.size()));
	return nullptr;
}
}  // namespace all_bullet_demos
