// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "Renderer.h"

#include <algorithm>
#include <cmath>

namespace caliber
{
namespace demo
{
std::uint32_t Image::pixel(int x, int y) const
{
	const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
	return (std::uint32_t(rgb[i]) << 16) | (std::uint32_t(rgb[i + 1]) << 8) | std::uint32_t(rgb[i + 2]);
}

void Camera::frame(const btVector3& aabbMin, const btVector3& aabbMax, btScalar aspect, const btVector3& viewDirection)
{
	btVector3 direction = viewDirection;
	if (!isFinite(direction) || direction.length2() < btScalar(1e-12)) direction = btVector3(-0.55f, -0.45f, -1);
	direction.normalize();
	target = (aabbMin + aabbMax) * btScalar(0.5);
	up = btFabs(direction.y()) > btScalar(0.99) ? btVector3(0, 0, -1) : btVector3(0, 1, 0);
	const btVector3 right = direction.cross(up).normalized();
	const btVector3 cameraUp = right.cross(direction);
	const double tanVertical = std::tan(double(fieldOfViewDegrees) * M_PI / 360.0);
	const double tanHorizontal = tanVertical * double(aspect > 0 ? aspect : 1);
	// The nearest eye (along -direction from the centre) that sees all eight corners: a corner at
	// (x, y) across the view and z along it needs |x| <= (d + z) tan(horizontal half angle), and the
	// same for y; 10% more leaves a border.
	double distance = 0;
	const btVector3 half = (aabbMax - aabbMin) * btScalar(0.5);
	for (int corner = 0; corner < 8; ++corner)
	{
		const btVector3 offset((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
		                       (corner & 4) ? half.z() : -half.z());
		const double x = std::fabs(double(offset.dot(right))), y = std::fabs(double(offset.dot(cameraUp)));
		const double z = double(offset.dot(direction));
		distance = std::max({distance, x / tanHorizontal - z, y / tanVertical - z, -z + 1e-3});
	}
	// A point-like box: keep at least a metre in view.
	distance = std::max(distance, 0.5 / tanVertical);
	eye = target - direction * btScalar(distance * 1.1);
}

Camera frameScene(const Scene& scene, const RenderOptions& options, const btVector3& viewDirection)
{
	btVector3 aabbMin(-1, -1, -1), aabbMax(1, 1, 1);
	if (scene.hasFocus())
	{
		aabbMin = scene.focusMin();
		aabbMax = scene.focusMax();
	}
	else
		scene.contentBounds(aabbMin, aabbMax);
	Camera camera;
	camera.frame(aabbMin, aabbMax, options.height > 0 ? btScalar(options.width) / btScalar(options.height) : 1,
	             viewDirection);
	return camera;
}

namespace
{
// A vertex in camera space (x right, y up, z forward) with the attributes shading needs.
struct ClipVertex
{
	double x, y, z;
	btVector3 world, normal;
};

// The pixel index floor(v) clamped to [0, size - 1], computed in double: a vertex just past the near
// plane can project millions of pixels away, beyond what an int holds.
int clampToPixels(double v, int size) { return int(std::min(double(size - 1), std::max(0.0, std::floor(v)))); }

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, double t)
{
	ClipVertex v;
	v.x = a.x + (b.x - a.x) * t;
	v.y = a.y + (b.y - a.y) * t;
	v.z = a.z + (b.z - a.z) * t;
	v.world = a.world.lerp(b.world, btScalar(t));
	v.normal = a.normal.lerp(b.normal, btScalar(t));
	return v;
}

// Everything one render() call shares: the target buffers and the camera's basis and projection.
class Rasterizer
{
public:
	Rasterizer(const Camera& camera, const RenderOptions& options)
	    : m_options(options),
	      m_samples(options.supersampling),
	      m_width(options.width * m_samples),
	      m_height(options.height * m_samples),
	      m_pixelSamples(std::size_t(m_width) * std::size_t(m_height)),
	      m_color(std::size_t(m_width) * std::size_t(m_height)),
	      m_depth(std::size_t(m_width) * std::size_t(m_height), 0.0f),
	      m_eye(camera.eye)
	{
		m_forward = (camera.target - camera.eye).normalized();
		m_right = m_forward.cross(camera.up);
		if (m_right.length2() < btScalar(1e-12)) m_right = m_forward.cross(btVector3(1, 0, 0));
		m_right.normalize();
		m_up = m_right.cross(m_forward);
		m_focal = 0.5 * m_height / std::tan(double(camera.fieldOfViewDegrees) * M_PI / 360.0);
		const double distance = double((camera.target - camera.eye).length());
		m_near = std::max(1e-4, 1e-3 * distance);
		std::fill(m_color.begin(), m_color.end(), options.background);
		// Light from above, from the camera's side and a little from its left; a weak fill from the right.
		m_key = (btVector3(0, 1, 0) - m_forward * btScalar(0.6) - m_right * btScalar(0.4)).normalized();
		m_fill = (m_right * btScalar(0.8) - m_forward * btScalar(0.3) + btVector3(0, btScalar(0.2), 0)).normalized();
	}

	void triangle(const SceneTriangle& t)
	{
		// Orient the face normal like the corner normals, then light the side that faces the camera.
		btVector3 face = (t.corner[1] - t.corner[0]).cross(t.corner[2] - t.corner[0]);
		if (face.dot(t.normal[0] + t.normal[1] + t.normal[2]) < 0) face = -face;
		const btScalar side = face.dot(m_eye - t.corner[0]) < 0 ? btScalar(-1) : btScalar(1);
		ClipVertex polygon[4];
		int count = 0;
		ClipVertex in[3];
		for (int i = 0; i < 3; ++i)
		{
			in[i] = toCamera(t.corner[i]);
			in[i].normal = t.normal[i] * side;
		}
		// Clip against the near plane (z >= near): a triangle becomes at most a quadrilateral.
		for (int i = 0; i < 3; ++i)
		{
			const ClipVertex& a = in[i];
			const ClipVertex& b = in[(i + 1) % 3];
			const bool aIn = a.z >= m_near, bIn = b.z >= m_near;
			if (aIn) polygon[count++] = a;
			if (aIn != bIn) polygon[count++] = lerp(a, b, (m_near - a.z) / (b.z - a.z));
		}
		for (int i = 1; i + 1 < count; ++i) rasterize(polygon[0], polygon[i], polygon[i + 1], t);
	}

	void line(const SceneLine& l)
	{
		ClipVertex a = toCamera(l.from), b = toCamera(l.to);
		if (a.z < m_near && b.z < m_near) return;
		if (a.z < m_near) a = lerp(a, b, (m_near - a.z) / (b.z - a.z));
		if (b.z < m_near) b = lerp(b, a, (m_near - b.z) / (a.z - b.z));
		double ax, ay, bx, by;
		project(a, ax, ay);
		project(b, bx, by);
		const double steps = std::ceil(std::max(std::fabs(bx - ax), std::fabs(by - ay)));
		// Long lines far off screen: stop at a bound that still crosses any image (no endless loops).
		const int n = int(std::min(steps, 4.0 * (m_width + m_height))) + 1;
		const int brush = std::max(1, m_options.lineWidth * m_samples);
		for (int i = 0; i <= n; ++i)
		{
			const double t = double(i) / n;
			// 1/z is linear in screen space, so the depth along the line interpolates it.
			const double inverseDepth = (1 - t) / a.z + t / b.z;
			splat(ax + (bx - ax) * t, ay + (by - ay) * t, inverseDepth, brush, l.color);
		}
	}

	void point(const ScenePoint& p)
	{
		const ClipVertex v = toCamera(p.position);
		if (v.z < m_near) return;
		double x, y;
		project(v, x, y);
		splat(x, y, 1 / v.z, 3 * m_samples, p.color);
	}

	/// Shades each pixel a triangle covers, with the nearest triangle's attributes (deferred, so that
	/// hidden surfaces cost no lighting).
	void shadeSurfaces()
	{
		for (std::size_t i = 0; i < m_pixelSamples.size(); ++i)
		{
			const Sample& sample = m_pixelSamples[i];
			if (sample.record < 0) continue;
			const Record& record = m_records[std::size_t(sample.record)];
			btVector3 world(0, 0, 0), normal(0, 0, 0);
			for (int k = 0; k < 3; ++k)
			{
				world += record.corner[k].world * sample.weight[k];
				normal += record.corner[k].normal * sample.weight[k];
			}
			m_color[i] = shade(world, normal, *record.triangle);
		}
	}

	void resolve(Image& image) const
	{
		image.width = m_options.width;
		image.height = m_options.height;
		image.rgb.assign(std::size_t(image.width) * std::size_t(image.height) * 3, 0);
		const double weight = 1.0 / (m_samples * m_samples);
		for (int y = 0; y < image.height; ++y)
			for (int x = 0; x < image.width; ++x)
			{
				double sum[3] = {0, 0, 0};
				for (int sy = 0; sy < m_samples; ++sy)
					for (int sx = 0; sx < m_samples; ++sx)
					{
						const btVector3& c = m_color[std::size_t(y * m_samples + sy) * std::size_t(m_width) +
						                             std::size_t(x * m_samples + sx)];
						for (int k = 0; k < 3; ++k) sum[k] += double(c[k]);
					}
				for (int k = 0; k < 3; ++k)
				{
					const double value = std::min(1.0, std::max(0.0, sum[k] * weight));
					image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3 + std::size_t(k)] =
					    std::uint8_t(std::lround(value * 255));
				}
			}
	}

private:
	ClipVertex toCamera(const btVector3& p) const
	{
		const btVector3 d = p - m_eye;
		ClipVertex v;
		v.x = double(d.dot(m_right));
		v.y = double(d.dot(m_up));
		v.z = double(d.dot(m_forward));
		v.world = p;
		v.normal = btVector3(0, 1, 0);
		return v;
	}

	void project(const ClipVertex& v, double& x, double& y) const
	{
		x = 0.5 * m_width + v.x * m_focal / v.z;
		y = 0.5 * m_height - v.y * m_focal / v.z;
	}

	void splat(double cx, double cy, double inverseDepth, int size, const btVector3& color)
	{
		const double half = 0.5 * size;
		// Wholly off the image (or not a number): nothing to draw.
		if (!(cx + half > 0 && cy + half > 0 && cx - half < m_width && cy - half < m_height)) return;
		const int x0 = clampToPixels(cx - half + 0.5, m_width), x1 = clampToPixels(cx + half - 0.5, m_width);
		const int y0 = clampToPixels(cy - half + 0.5, m_height), y1 = clampToPixels(cy + half - 0.5, m_height);
		for (int y = y0; y <= y1; ++y)
			for (int x = x0; x <= x1; ++x)
			{
				const std::size_t i = std::size_t(y) * std::size_t(m_width) + std::size_t(x);
				// A small bias lets a line on a surface win against that surface.
				if (m_options.linesOnTop || inverseDepth * 1.002 >= double(m_depth[i])) m_color[i] = color;
			}
	}

	void rasterize(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, const SceneTriangle& t)
	{
		const ClipVertex* v[3] = {&a, &b, &c};
		const int record = int(m_records.size());
		bool covered = false;
		double sx[3], sy[3], w[3];
		for (int i = 0; i < 3; ++i)
		{
			project(*v[i], sx[i], sy[i]);
			w[i] = 1 / v[i]->z;
		}
		const double area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
		if (!(std::fabs(area) > 1e-12)) return;  // edge-on or degenerate: covers no pixel centre
		const double minX = std::min({sx[0], sx[1], sx[2]}), maxX = std::max({sx[0], sx[1], sx[2]});
		const double minY = std::min({sy[0], sy[1], sy[2]}), maxY = std::max({sy[0], sy[1], sy[2]});
		if (!(maxX >= 0 && maxY >= 0 && minX < m_width && minY < m_height)) return;  // wholly off the image
		const int x0 = clampToPixels(minX, m_width), x1 = clampToPixels(std::ceil(maxX), m_width);
		const int y0 = clampToPixels(minY, m_height), y1 = clampToPixels(std::ceil(maxY), m_height);
		for (int y = y0; y <= y1; ++y)
		{
			const double py = y + 0.5;
			for (int x = x0; x <= x1; ++x)
			{
				const double px = x + 0.5;
				double l[3];
				l[0] = ((sx[1] - px) * (sy[2] - py) - (sy[1] - py) * (sx[2] - px)) / area;
				l[1] = ((sx[2] - px) * (sy[0] - py) - (sy[2] - py) * (sx[0] - px)) / area;
				l[2] = 1 - l[0] - l[1];
				if (l[0] < 0 || l[1] < 0 || l[2] < 0) continue;
				const double inverseDepth = l[0] * w[0] + l[1] * w[1] + l[2] * w[2];
				const std::size_t i = std::size_t(y) * std::size_t(m_width) + std::size_t(x);
				if (inverseDepth <= double(m_depth[i])) continue;
				m_depth[i] = float(inverseDepth);
				// Perspective-correct weights for the attributes; the pixel is shaded once, in
				// shadeSurfaces(), by the triangle that ends up nearest.
				Sample& sample = m_pixelSamples[i];
				sample.record = record;
				for (int k = 0; k < 3; ++k) sample.weight[k] = btScalar(l[k] * w[k] / inverseDepth);
				covered = true;
			}
		}
		if (covered) m_records.push_back(Record{{a, b, c}, &t});
	}

	btVector3 shade(const btVector3& world, btVector3 normal, const SceneTriangle& t) const
	{
		const btScalar length = normal.length();
		normal = length > btScalar(1e-12) ? normal / length : -m_forward;
		const btVector3 toEye = (m_eye - world).normalized();
		const btScalar key = btMax(btScalar(0), normal.dot(m_key));
		const btScalar fill = btMax(btScalar(0), normal.dot(m_fill));
		btVector3 base = t.color;
		if (t.checker)
		{
			// Checker in the plane of the two axes the surface spans most.
			const int axis = normal.absolute().maxAxis();
			const int u = (axis + 1) % 3, v = (axis + 2) % 3;
			const long cell = long(std::floor(double(world[u]))) + long(std::floor(double(world[v])));
			if (cell % 2 != 0) base *= btScalar(0.88);
		}
		const btVector3 halfway = (m_key + toEye).normalized();
		// x^32 by five squarings: powf was a seventh of a picture's instructions.
		btScalar specular = btMax(btScalar(0), normal.dot(halfway));
		for (int i = 0; i < 5; ++i) specular *= specular;
		specular *= btScalar(0.15);
		btVector3 color = base * (btScalar(0.32) + btScalar(0.6) * key + btScalar(0.18) * fill);
		color += btVector3(specular, specular, specular);
		return color;
	}

	const RenderOptions& m_options;
	const int m_samples, m_width, m_height;
	// A rasterized (clipped) triangle, and which of its pixels it owns: shading waits for the last one.
	struct Record
	{
		ClipVertex corner[3];
		const SceneTriangle* triangle;
	};
	struct Sample
	{
		int record = -1;
		btScalar weight[3] = {0, 0, 0};
	};
	std::vector<Record> m_records;
	std::vector<Sample> m_pixelSamples;
	std::vector<btVector3> m_color;
	std::vector<float> m_depth;  // 1 / depth; 0 is the far background
	btVector3 m_eye, m_forward, m_right, m_up, m_key, m_fill;
	double m_focal = 1, m_near = 1e-3;
};
}  // namespace

bool render(const Scene& scene, const Camera& camera, const RenderOptions& options, Image& image, std::string& error)
{
	image = Image();
	if (options.width < 1 || options.height < 1 || options.width > kMaxImageSide || options.height > kMaxImageSide)
	{
		error = "image size " + std::to_string(options.width) + " x " + std::to_string(options.height) +
		        " is not usable: each side must be from 1 to " + std::to_string(kMaxImageSide) + " pixels";
		return false;
	}
	if (options.supersampling < 1 || options.supersampling > 4)
	{
		error = "supersampling " + std::to_string(options.supersampling) + " is not usable: it must be from 1 to 4";
		return false;
	}
	if (!isFinite(camera.eye) || !isFinite(camera.target) || !isFinite(camera.up) ||
	    (camera.target - camera.eye).length2() <= btScalar(0) ||
	    !(camera.fieldOfViewDegrees > btScalar(1) && camera.fieldOfViewDegrees < btScalar(179)))
	{
		error =
		    "the camera is not usable: eye and target must be finite and apart, and the field of view between 1 "
		    "and 179 degrees";
		return false;
	}
	Rasterizer rasterizer(camera, options);
	for (const SceneTriangle& t : scene.triangles()) rasterizer.triangle(t);
	rasterizer.shadeSurfaces();
	for (const SceneLine& l : scene.lines()) rasterizer.line(l);
	for (const ScenePoint& p : scene.points()) rasterizer.point(p);
	rasterizer.resolve(image);
	return true;
}
}  // namespace demo
}  // namespace caliber
