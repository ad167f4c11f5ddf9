// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "SoftBodyScene.h"

#include "BulletSoftBody/btSoftBody.h"

namespace caliber
{
namespace demo
{
int addSoftBody(Scene& scene, const btSoftBody& body, const btVector3& color)
{
	int added = 0;
	for (int f = 0; f < body.m_faces.size(); ++f)
	{
		const btSoftBody::Face& face = body.m_faces[f];
		btVector3 corner[3], normal[3];
		bool smooth = true;
		for (int k = 0; k < 3; ++k)
		{
			corner[k] = face.m_n[k]->m_x;
			normal[k] = face.m_n[k]->m_n;
			// A node normal is the sum of its faces' normals; a fold can cancel it (then shade flat).
			if (!(normal[k].length2() > btScalar(1e-12))) smooth = false;
		}
		if (smooth)
			scene.addSmoothTriangle(corner, normal, color);
		else
			scene.addFlatTriangle(corner[0], corner[1], corner[2], color);
		++added;
	}
	// A rope or a bare net has only links; its bending links would only double the drawing.
	if (body.m_faces.size() == 0)
		for (int l = 0; l < body.m_links.size(); ++l)
		{
			const btSoftBody::Link& link = body.m_links[l];
			if (link.m_bbending) continue;
			scene.addLine(link.m_n[0]->m_x, link.m_n[1]->m_x, color);
			++added;
		}
	return added;
}

bool softBodyNodeBounds(const btSoftBody& body, btVector3& aabbMin, btVector3& aabbMax)
{
	bool any = false;
	for (int n = 0; n < body.m_nodes.size(); ++n)
	{
		const btVector3& x = body.m_nodes[n].m_x;
		if (!isFinite(x)) continue;
		if (!any)
		{
			aabbMin = aabbMax = x;
			any = true;
		}
		aabbMin.setMin(x);
		aabbMax.setMax(x);
	}
	return any;
}
}  // namespace demo
}  // namespace caliber
