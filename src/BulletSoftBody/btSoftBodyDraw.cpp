// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBodyHelpers' drawing functions on btIDebugDraw.

#include <cstdio>

#include "BulletSoftBody/btSoftBodyHelpers.h"
#include "btSoftBodyClusters.h"

namespace
{
void drawCross(btIDebugDraw* idraw, const btVector3& p, btScalar size, const btVector3& color)
{
	idraw->drawLine(p - btVector3(size, 0, 0), p + btVector3(size, 0, 0), color);
	idraw->drawLine(p - btVector3(0, size, 0), p + btVector3(0, size, 0), color);
	idraw->drawLine(p - btVector3(0, 0, size), p + btVector3(0, 0, size), color);
}
}  // namespace

void btSoftBodyHelpers::Draw(btSoftBody* psb, btIDebugDraw* idraw, int drawflags)
{
	if (!psb || !idraw) return;
	const btVector3 nodeColor(1, 1, 1), linkColor(0, 0, 0), faceColor(btScalar(0.3), btScalar(0.3), btScalar(0.8));
	if (drawflags & fDrawFlags::Nodes)
		for (int i = 0; i < psb->m_nodes.size(); ++i) drawCross(idraw, psb->m_nodes[i].m_x, btScalar(0.1), nodeColor);
	if (drawflags & fDrawFlags::Links)
		for (int i = 0; i < psb->m_links.size(); ++i)
		{
			const btSoftBody::Link& l = psb->m_links[i];
			if (l.m_material && !(l.m_material->m_flags & btSoftBody::fMaterial::DebugDraw)) continue;
			idraw->drawLine(l.m_n[0]->m_x, l.m_n[1]->m_x, linkColor);
		}
	if (drawflags & fDrawFlags::Normals)
		for (int i = 0; i < psb->m_nodes.size(); ++i)
		{
			const btSoftBody::Node& n = psb->m_nodes[i];
			idraw->drawLine(n.m_x, n.m_x + n.m_n * btScalar(0.25), btVector3(0, 1, 0));
		}
	if (drawflags & fDrawFlags::Faces)
		for (int i = 0; i < psb->m_faces.size(); ++i)
		{
			const btSoftBody::Face& f = psb->m_faces[i];
			idraw->drawTriangle(f.m_n[0]->m_x, f.m_n[1]->m_x, f.m_n[2]->m_x, faceColor, 1);
		}
	if (drawflags & fDrawFlags::Tetras)
		for (int i = 0; i < psb->m_tetras.size(); ++i)
		{
			const btSoftBody::Tetra& t = psb->m_tetras[i];
			for (int a = 0; a < 4; ++a)
				for (int b = a + 1; b < 4; ++b)
					idraw->drawLine(t.m_n[a]->m_x, t.m_n[b]->m_x,
					                btVector3(btScalar(0.3), btScalar(0.8), btScalar(0.3)));
		}
	if (drawflags & fDrawFlags::Clusters)
		for (int i = 0; i < psb->m_clusters.size(); ++i)
		{
			// Each cluster as spokes from its centre to its nodes, in a colour of its own.
			const btSoftBody::Cluster& c = *psb->m_clusters[i];
			const btVector3 color(btScalar((i * 37) % 10) / 10, btScalar((i * 61) % 10) / 10,
			                      btScalar((i * 83) % 10) / 10);
			const btVector3 com = btSoftBody::clusterCom(&c);
			for (int j = 0; j < c.m_nodes.size(); ++j) idraw->drawLine(com, c.m_nodes[j]->m_x, color);
		}
	if (drawflags & fDrawFlags::Joints)
		for (int i = 0; i < psb->m_joints.size(); ++i)
		{
			// The joint's point (or axis) as each side carries it, and a line between the two.
			const btSoftBody::Joint& j = *psb->m_joints[i];
			const btVector3 color(1, btScalar(0.5), 0);
			if (j.Type() == btSoftBody::Joint::eType::Angular)
			{
				const btVector3 o = j.m_bodies[0].xform().getOrigin();
				idraw->drawLine(o, o + j.m_bodies[0].xform().getBasis() * j.m_refs[0], color);
				continue;
			}
			const btVector3 a = j.m_bodies[0].xform() * j.m_refs[0], b = j.m_bodies[1].xform() * j.m_refs[1];
			drawCross(idraw, a, btScalar(0.1), color);
			idraw->drawLine(a, b, color);
		}
	if (drawflags & fDrawFlags::Contacts)
		for (int i = 0; i < psb->m_rcontacts.size(); ++i)
		{
			const btSoftBody::RContact& c = psb->m_rcontacts[i];
			idraw->drawLine(c.m_node->m_x, c.m_node->m_x + c.m_cti.m_normal * btScalar(0.2), btVector3(1, 0, 0));
		}
	if (drawflags & fDrawFlags::Anchors)
		for (int i = 0; i < psb->m_anchors.size(); ++i)
		{
			const btSoftBody::Anchor& a = psb->m_anchors[i];
			const btVector3 q = a.m_body->getWorldTransform() * a.m_local;
			drawCross(idraw, a.m_node->m_x, btScalar(0.25), btVector3(1, 0, 0));
			drawCross(idraw, q, btScalar(0.25), btVector3(0, 1, 0));
			idraw->drawLine(a.m_node->m_x, q, btVector3(1, 1, 1));
		}
	if (drawflags & fDrawFlags::Notes)
		for (int i = 0; i < psb->m_notes.size(); ++i)
		{
			const btSoftBody::Note& n = psb->m_notes[i];
			btVector3 p = n.m_offset;
			for (int j = 0; j < n.m_rank; ++j) p += n.m_nodes[j]->m_x * n.m_coords[j];
			idraw->draw3dText(p, n.m_text);
		}
	if (drawflags & fDrawFlags::NodeTree) DrawNodeTree(psb, idraw);
	if (drawflags & fDrawFlags::FaceTree) DrawFaceTree(psb, idraw);
}

void btSoftBodyHelpers::DrawInfos(btSoftBody* psb, btIDebugDraw* idraw, bool masses, bool areas, bool stress)
{
	(void)stress;
	if (!psb || !idraw) return;
	for (int i = 0; i < psb->m_nodes.size(); ++i)
	{
		const btSoftBody::Node& n = psb->m_nodes[i];
		char text[64] = "";
		int len = 0;
		if (masses) len += std::snprintf(text + len, sizeof(text) - len, " M(%.2f)", double(psb->getMass(i)));
		if (areas && len < int(sizeof(text)))
			len += std::snprintf(text + len, sizeof(text) - len, " A(%.2f)", double(n.m_area));
		if (len > 0) idraw->draw3dText(n.m_x, text);
	}
}

void btSoftBodyHelpers::DrawNodeTree(btSoftBody* psb, btIDebugDraw* idraw, int mindepth, int maxdepth)
{
	(void)mindepth;
	(void)maxdepth;
	if (!psb || !idraw) return;
	idraw->drawAabb(psb->m_bounds[0], psb->m_bounds[1], btVector3(1, 0, 1));
}

void btSoftBodyHelpers::DrawFaceTree(btSoftBody* psb, btIDebugDraw* idraw, int mindepth, int maxdepth)
{
	DrawNodeTree(psb, idraw, mindepth, maxdepth);
}

namespace
{
// The boxes of a tree's nodes from depth mindepth down to maxdepth (-1: the leaves), as Bullet draws its trees.
void drawTree(btIDebugDraw* idraw, const btDbvtNode* node, int depth, int mindepth, int maxdepth)
{
	if (!node || (maxdepth >= 0 && depth > maxdepth)) return;
	if (node->isinternal())
	{
		drawTree(idraw, node->childs[0], depth + 1, mindepth, maxdepth);
		drawTree(idraw, node->childs[1], depth + 1, mindepth, maxdepth);
	}
	if (depth >= mindepth)
		idraw->drawAabb(node->volume.Mins(), node->volume.Maxs(),
		                node->isinternal() ? btVector3(1, 0, 1) : btVector3(0, 1, 1));
}
}  // namespace

void btSoftBodyHelpers::DrawClusterTree(btSoftBody* psb, btIDebugDraw* idraw, int mindepth, int maxdepth)
{
	if (!psb || !idraw) return;
	// The tree as the clusters stand now (a body not stepped since its clusters were made has none yet; the
	// tree only culls, so bringing it up to date changes no result).
	if (psb->m_clusters.size() > 0) caliber::updateClusterTree(*psb);
	drawTree(idraw, psb->m_cdbvt.m_root, 0, mindepth, maxdepth);
}

void btSoftBodyHelpers::DrawFrame(btSoftBody* psb, btIDebugDraw* idraw)
{
	if (!psb || !idraw || !psb->m_pose.m_bframe) return;
	const btVector3 com = psb->m_pose.m_com;
	const btMatrix3x3& rot = psb->m_pose.m_rot;
	const btScalar len = 1;
	idraw->drawLine(com, com + rot.getColumn(0) * len, btVector3(1, 0, 0));
	idraw->drawLine(com, com + rot.getColumn(1) * len, btVector3(0, 1, 0));
	idraw->drawLine(com, com + rot.getColumn(2) * len, btVector3(0, 0, 1));
	for (int i = 0; i < psb->m_pose.m_pos.size() && i < psb->m_nodes.size(); ++i)
		idraw->drawLine(psb->m_nodes[i].m_x, com + rot * psb->m_pose.m_pos[i], btVector3(1, 0, 1));
}
