// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALL_BULLET_DEMOS_GL_RENDERER_H
#define CALIBER_ALL_BULLET_DEMOS_GL_RENDERER_H
// Draws a caliber::demo::Scene (the same scene the headless pictures use) with OpenGL 3.3 core:
// lit triangles with the software renderer's lights and checker, then lines and points on top.

#include <string>
#include <vector>

#include "BitmapFont.h"
#include "Renderer.h"
#include "Scene.h"

namespace all_bullet_demos
{
/// Owns the shaders and buffers; needs a current OpenGL 3.3 core context for every call.
class GlRenderer
{
public:
	/// Compiles the shaders and makes the buffers. False with the compiler's message in error.
	bool init(std::string& error);
	/// Frees what init() made (the context must still be current).
	void shutdown();
	/// Clears the viewport to the background and draws scene as camera sees it.
	void draw(const caliber::demo::Scene& scene, const caliber::demo::Camera& camera, int width, int height,
	          bool wireframe);
	/// Draws text cells (BitmapFont's layout, in window pixels, y down) over what is drawn, in the
	/// colour (0..1) with a near-white shadow one pixel down and right, so dark text reads on any background.
	void drawText(const std::vector<caliber::demo::TextCell>& cells, const btVector3& color, int width, int height);

private:
	unsigned m_solidProgram = 0, m_lineProgram = 0;
	unsigned m_solidVao = 0, m_solidVbo = 0, m_lineVao = 0, m_lineVbo = 0;
	std::vector<float> m_solidData, m_lineData, m_pointData, m_textData;
};
}  // namespace all_bullet_demos

#endif
