// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "Scene.h"

#include <cmath>

namespace caliber
{
namespace demo
{
bool isFinite(const btVector3& v)
{
	return std::isfinite(double(v.x())) && std::isfinite(double(v.y())) && std::isfinite(double(v.z()));
}

void Scene::addFlatTriangle(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& color,
                            bool checker)
{
	if (!isFinite(a) || !isFinite(b) || !isFinite(c))
	{
		++m_skippedNonFinite;
		return;
	}
	SceneTriangle t;
	t.corner[0] = a;
	t.corner[1] = b;
	t.corner[2] = c;
	btVector3 n = (b - a).cross(c - a);
	const btScalar length = n.length();
	// A degenerate (zero-area) triangle covers no pixel; any normal will do.
	n = length > btScalar(0) ? n / length : btVector3(0, 1, 0);
	t.normal[0] = t.normal[1] = t.normal[2] = n;
	t.color = color;
	t.checker = checker;
	m_triangles.push_back(t);
}

void Scene::addSmoothTriangle(const btVector3 corner[3], const btVector3 normal[3], const btVector3& color)
{
	for (int i = 0; i < 3; ++i)
		if (!isFinite(corner[i]) || !isFinite(normal[i]))
		{
			++m_skippedNonFinite;
			return;
		}
	SceneTriangle t;
	for (int i = 0; i < 3; ++i)
	{
		t.corner[i] = corner[i];
		t.normal[i] = normal[i];
	}
	t.color = color;
	m_triangles.push_back(t);
}

void Scene::addLine(const btVector3& from, const btVector3& to, const btVector3& color)
{
	if (!isFinite(from) || !isFinite(to))
	{
		++m_skippedNonFinite;
		return;
	}
	m_lines.push_back(SceneLine{from, to, color});
}

void Scene::addPoint(const btVector3& position, const btVector3& color)
{
	if (!isFinite(position))
	{
		++m_skippedNonFinite;
		return;
	}
	m_points.push_back(ScenePoint{position, color});
}

void Scene::focusOn(const btVector3& aabbMin, const btVector3& aabbMax)
{
	if (!isFinite(aabbMin) || !isFinite(aabbMax)) return;
	if (!m_hasFocus)
	{
		m_focusMin = aabbMin;
		m_focusMax = aabbMax;
		m_hasFocus = true;
		return;
	}
	m_focusMin.setMin(aabbMin);
	m_focusMax.setMax(aabbMax);
}

bool Scene::contentBounds(btVector3& aabbMin, btVector3& aabbMax) const
{
	bool any = false;
	auto grow = [&](const btVector3& p)
	{
		if (!any)
		{
			aabbMin = aabbMax = p;
			any = true;
		}
		aabbMin.setMin(p);
		aabbMax.setMax(p);
	};
	for (const SceneTriangle& t : m_triangles)
		for (const btVector3& c : t.corner) grow(c);
	for (const SceneLine& l : m_lines)
	{
		grow(l.from);
		grow(l.to);
	}
	for (const ScenePoint& p : m_points) grow(p.position);
	return any;
}

void Scene::append(const Scene& other)
{
	// A vector's insert from its own range is undefined: appending itself appends a copy.
	if (&other == this)
	{
		const Scene copy = other;
		append(copy);
		return;
	}
	m_triangles.insert(m_triangles.end(), other.m_triangles.begin(), other.m_triangles.end());
	m_lines.insert(m_lines.end(), other.m_lines.begin(), other.m_lines.end());
	m_points.insert(m_points.end(), other.m_points.begin(), other.m_points.end());
}

void Scene::clear()
{
	m_triangles.clear();
	m_lines.clear();
	m_points.clear();
	m_hasFocus = false;
	m_skippedNonFinite = 0;
}
}  // namespace demo
}  // namespace caliber
