// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBodyHelpers::CreateFromTetGenData: volumes from TetGen's .node, .ele and .face text.

#include <cstdlib>
#include <unordered_set>
#include <vector>

#include "BulletSoftBody/btSoftBodyHelpers.h"
#include "btSoftBodyInternal.h"

namespace
{
// Reads whitespace-separated numbers, skipping '#' comments to the end of their line.
class NumberReader
{
public:
	explicit NumberReader(const char* text) : m_at(text) {}

	bool next(double& value)
	{
		while (*m_at)
		{
			if (*m_at == '#')
			{
				while (*m_at && *m_at != '\n') ++m_at;
				continue;
			}
			if (*m_at == ' ' || *m_at == '\t' || *m_at == '\r' || *m_at == '\n')
			{
				++m_at;
				continue;
			}
			char* end = 0;
			value = std::strtod(m_at, &end);
			if (end == m_at) return false;  // not a number: the text is malformed
			m_at = end;
			return true;
		}
		return false;
	}
	bool nextInt(int& value)
	{
		double v = 0;
		if (!next(v) || v != double(int(v))) return false;
		value = int(v);
		return true;
	}

private:
	const char* m_at;
};

// Links each pair once: a set of sorted node pairs.
struct LinkSet
{
	btSoftBody& body;
	std::unordered_set<long long> made;

	void link(int a, int b)
	{
		if (a == b) return;
		const long long key = (long long)btMin(a, b) * 0x100000000LL + btMax(a, b);
		if (made.insert(key).second) body.appendLink(a, b);
	}
};

btSoftBody* failed(btSoftBodyWorldInfo& worldInfo, const char* message)
{
	btAssert(!"btSoftBodyHelpers::CreateFromTetGenData: malformed TetGen data");
	caliber::softBodyWarning(message);
	return new btSoftBody(&worldInfo);
}
}  // namespace

btSoftBody* btSoftBodyHelpers::CreateFromTetGenData(btSoftBodyWorldInfo& worldInfo, const char* ele, const char* face,
                                                    const char* node, bool bfacelinks, bool btetralinks,
                                                    bool bfacesfromtetras)
{
	if (!node || !ele) return failed(worldInfo, "Caliber: CreateFromTetGenData: no node or ele data; empty body\n");
	// .node: <points> <dimension 3> <attributes> <boundary markers 0|1>, then <index> x y z [attr...] [marker].
	NumberReader nodes(node);
	int count = 0, dimension = 0, attributes = 0, markers = 0;
	if (!nodes.nextInt(count) || !nodes.nextInt(dimension) || !nodes.nextInt(attributes) || !nodes.nextInt(markers) ||
	    count < 0 || dimension != 3 || attributes < 0 || markers < 0 || markers > 1)
		return failed(worldInfo, "Caliber: CreateFromTetGenData: bad .node header; empty body\n");
	std::vector<btVector3> x(count);
	int base = 0;
	for (int i = 0; i < count; ++i)
	{
		int index = 0;
		double c[3] = {0, 0, 0}, skip = 0;
		if (!nodes.nextInt(index) || !nodes.next(c[0]) || !nodes.next(c[1]) || !nodes.next(c[2]))
			return failed(worldInfo, "Caliber: CreateFromTetGenData: truncated .node data; empty body\n");
		for (int a = 0; a < attributes + markers; ++a) nodes.next(skip);
		if (i == 0) base = index;  // TetGen numbers from 0 or from 1
		if (index - base != i)
			return failed(worldInfo, "Caliber: CreateFromTetGenData: .node indices out of order; empty body\n");
		x[i].setValue(btScalar(c[0]), btScalar(c[1]), btScalar(c[2]));
	}
	btSoftBody* psb = new btSoftBody(&worldInfo, count, count ? &x[0] : 0, 0);
	LinkSet links{*psb, {}};
	auto readIndex = [&](NumberReader& r, int& out) { return r.nextInt(out) && (out -= base) >= 0 && out < count; };
	// .ele: <tetras> <nodes per tetra 4> <region attribute 0|1>, then <index> n0 n1 n2 n3 [attribute].
	NumberReader tetras(ele);
	int tetraCount = 0, perTetra = 0, region = 0;
	if (!tetras.nextInt(tetraCount) || !tetras.nextInt(perTetra) || !tetras.nextInt(region) || tetraCount < 0 ||
	    perTetra != 4 || region < 0 || region > 1)
	{
		delete psb;
		return failed(worldInfo, "Caliber: CreateFromTetGenData: bad .ele header; empty body\n");
	}
	for (int t = 0; t < tetraCount; ++t)
	{
		int index = 0, n[4];
		double skip = 0;
		if (!tetras.nextInt(index) || !readIndex(tetras, n[0]) || !readIndex(tetras, n[1]) ||
		    !readIndex(tetras, n[2]) || !readIndex(tetras, n[3]))
		{
			delete psb;
			return failed(worldInfo, "Caliber: CreateFromTetGenData: bad .ele data; empty body\n");
		}
		if (region) tetras.next(skip);
		psb->appendTetra(n[0], n[1], n[2], n[3]);
		if (btetralinks)
			for (int a = 0; a < 4; ++a)
				for (int b = a + 1; b < 4; ++b) links.link(n[a], n[b]);
		if (bfacesfromtetras)
		{
			// Outward winding for TetGen's positive orientation (n3 on the positive side of n0 n1 n2).
			psb->appendFace(n[0], n[2], n[1]);
			psb->appendFace(n[0], n[1], n[3]);
			psb->appendFace(n[1], n[2], n[3]);
			psb->appendFace(n[0], n[3], n[2]);
		}
	}
	// .face: <faces> <boundary markers 0|1>, then <index> n0 n1 n2 [marker].
	if (face)
	{
		NumberReader faces(face);
		int faceCount = 0, faceMarkers = 0;
		if (!faces.nextInt(faceCount) || !faces.nextInt(faceMarkers) || faceCount < 0 || faceMarkers < 0 ||
		    faceMarkers > 1)
		{
			delete psb;
			return failed(worldInfo, "Caliber: CreateFromTetGenData: bad .face header; empty body\n");
		}
		for (int f = 0; f < faceCount; ++f)
		{
			int index = 0, n[3];
			double skip = 0;
			if (!faces.nextInt(index) || !readIndex(faces, n[0]) || !readIndex(faces, n[1]) || !readIndex(faces, n[2]))
			{
				delete psb;
				return failed(worldInfo, "Caliber: CreateFromTetGenData: bad .face data; empty body\n");
			}
			if (faceMarkers) faces.next(skip);
			psb->appendFace(n[0], n[1], n[2]);
			if (bfacelinks)
				for (int a = 0; a < 3; ++a) links.link(n[a], n[(a + 1) % 3]);
		}
	}
	return psb;
}
