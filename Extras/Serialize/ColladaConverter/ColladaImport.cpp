// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// COLLADA 1.4 physics import with tinyxml2. The reader follows the scene: <scene> names the physics scene,
// whose model instances name rigid bodies (in <library_physics_models>) and the nodes (in
// <library_visual_scenes>) that place them. Every reference is checked; the first problem ends the import.
#include <tinyxml2.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"
#include "ColladaPhysics.h"

using tinyxml2::XMLElement;

namespace caliber
{
namespace
{
const double kMaxMagnitude = 1e15;

class Reader
{
public:
	explicit Reader(ColladaPhysicsScene& scene) : m_scene(scene) {}

	bool run(const char* text, std::size_t size)
	{
		if (m_document.Parse(text, size) != tinyxml2::XML_SUCCESS)
		{
			m_scene.error =
			    "line " + std::to_string(m_document.ErrorLineNum()) + ": malformed XML (" + m_document.ErrorStr() + ")";
			return false;
		}
		const XMLElement* root = m_document.RootElement();
		if (!root || std::strcmp(root->Name(), "COLLADA") != 0)
			return fail(root, "the document is not COLLADA (its root element is not <COLLADA>)");
		collectIds(root);
		if (!readAsset(root) || !readNodes(root)) return false;
		const XMLElement* physicsScene = nullptr;
		if (const XMLElement* instance = path(root, {"scene", "instance_physics_scene"}))
		{
			if (!(physicsScene = resolve(instance, "url", "physics_scene"))) return false;
		}
		else
			physicsScene = path(root, {"library_physics_scenes", "physics_scene"});
		if (!physicsScene) return fail(root, "the document has no physics scene");
		if (const XMLElement* common = physicsScene->FirstChildElement("technique_common"))
		{
			if (const XMLElement* gravity = common->FirstChildElement("gravity"))
			{
				if (!vector(gravity, m_scene.gravity)) return false;
				m_scene.gravity = toWorld(m_scene.gravity * m_scale);
			}
			if (const XMLElement* step = common->FirstChildElement("time_step"))
			{
				if (!numbers(step, 1, &m_scene.timeStep)) return false;
				if (!(m_scene.timeStep > 0)) return fail(step, "the time step must be positive");
			}
		}
		for (const XMLElement* model = physicsScene->FirstChildElement("instance_physics_model"); model;
		     model = model->NextSiblingElement("instance_physics_model"))
		{
			const XMLElement* physicsModel = resolve(model, "url", "physics_model");
			if (!physicsModel) return false;
			m_instancedBodies.clear();
			for (const XMLElement* instance = model->FirstChildElement("instance_rigid_body"); instance;
			     instance = instance->NextSiblingElement("instance_rigid_body"))
				if (!readBody(physicsModel, instance)) return false;
			for (const XMLElement* instance = model->FirstChildElement("instance_rigid_constraint"); instance;
			     instance = instance->NextSiblingElement("instance_rigid_constraint"))
				if (!readJoint(physicsModel, instance)) return false;
		}
		return true;
	}

private:
	// <asset>'s unit and up axis: lengths are multiplied by m_scale (metres per unit) and world vectors
	// turned by m_up (the document's up axis to +y). Body-local values (shapes, attachment frames) are only
	// scaled, since the body's pose carries the turn.
	bool readAsset(const XMLElement* root)
	{
		const XMLElement* asset = root->FirstChildElement("asset");
		if (!asset) return true;
		if (const XMLElement* unit = asset->FirstChildElement("unit"))
			if (const char* meter = unit->Attribute("meter"))
			{
				const char* end = meter + std::strlen(meter);
				btScalar value = 0;
				const std::from_chars_result r = std::from_chars(meter, end, value);
				if (r.ec != std::errc() || r.ptr != end || !(value >= btScalar(1e-6) && value <= btScalar(1e6)))
					return fail(unit, "<unit>'s meter must be a number from 1e-6 to 1e6");
				m_scale = value;
			}
		if (const XMLElement* up = asset->FirstChildElement("up_axis"))
		{
			std::string axis = up->GetText() ? up->GetText() : "";
			const std::size_t first = axis.find_first_not_of(" \t\r\n");
			axis = first == std::string::npos ? "" : axis.substr(first, axis.find_last_not_of(" \t\r\n") - first + 1);
			if (axis == "X_UP")  // x to y, y to -x
				m_up.setValue(0, -1, 0, 1, 0, 0, 0, 0, 1);
			else if (axis == "Z_UP")  // z to y, y to -z
				m_up.setValue(1, 0, 0, 0, 0, 1, 0, -1, 0);
			else if (axis != "Y_UP")
				return fail(up, "<up_axis> must be X_UP, Y_UP or Z_UP");
			m_turn = axis != "Y_UP";
		}
		return true;
	}

	btVector3 toWorld(const btVector3& v) const { return m_turn ? m_up * v : v; }

	bool fail(const XMLElement* at, const std::string& message)
	{
		m_scene.error = "line " + std::to_string(at ? at->GetLineNum() : 0) + ": " + message;
		return false;
	}

	static const XMLElement* path(const XMLElement* from, std::initializer_list<const char*> names)
	{
		for (const char* name : names)
			if (!(from = from->FirstChildElement(name))) return nullptr;
		return from;
	}

	void collectIds(const XMLElement* element)
	{
		if (const char* id = element->Attribute("id")) m_ids.emplace(id, element);
		for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
			collectIds(child);
	}

	// The element a "#id" attribute points to, which must be a <kind>.
	const XMLElement* resolve(const XMLElement* at, const char* attribute, const char* kind)
	{
		const char* url = at->Attribute(attribute);
		if (!url || url[0] != '#')
		{
			fail(at, std::string("<") + at->Name() + "> needs a " + attribute + " of the form \"#id\"");
			return nullptr;
		}
		const auto found = m_ids.find(url + 1);
		if (found == m_ids.end() || std::strcmp(found->second->Name(), kind) != 0)
		{
			fail(at, std::string("'") + url + "' names no <" + kind + ">");
			return nullptr;
		}
		return found->second;
	}

	// Exactly count finite numbers of sensible size from the element's text.
	bool numbers(const XMLElement* element, int count, btScalar* out)
	{
		std::vector<btScalar> values;
		if (!numberList(element, values)) return false;
		if (int(values.size()) != count)
			return fail(element, std::string("<") + element->Name() + "> needs " + std::to_string(count) +
			                         " numbers, found " + std::to_string(values.size()));
		for (int i = 0; i < count; ++i) out[i] = values[i];
		return true;
	}

	bool numberList(const XMLElement* element, std::vector<btScalar>& values)
	{
		values.clear();
		const char* text = element->GetText();
		const char* end = text ? text + std::strlen(text) : nullptr;
		while (text && text < end)
		{
			while (text < end && (*text == ' ' || *text == '\t' || *text == '\n' || *text == '\r')) ++text;
			if (text == end) break;
			const char* start = text;
			if (*start == '+') ++start;
			btScalar value = 0;
			const std::from_chars_result r = std::from_chars(start, end, value);
			if (r.ec == std::errc::result_out_of_range)
				return fail(element,
				            std::string("<") + element->Name() + "> holds a number that is not finite or beyond 1e15");
			if (r.ec != std::errc() ||
			    (r.ptr < end && !(*r.ptr == ' ' || *r.ptr == '\t' || *r.ptr == '\n' || *r.ptr == '\r')))
				return fail(element, std::string("<") + element->Name() + "> holds something that is not a number");
			if (!std::isfinite(value) || std::fabs(double(value)) > kMaxMagnitude)
				return fail(element,
				            std::string("<") + element->Name() + "> holds a number that is not finite or beyond 1e15");
			values.push_back(value);
			text = r.ptr;
		}
		return true;
	}

	bool vector(const XMLElement* element, btVector3& out)
	{
		btScalar v[3] = {0, 0, 0};
		if (!numbers(element, 3, v)) return false;
		out.setValue(v[0], v[1], v[2]);
		return true;
	}

	// translate, rotate and matrix children of element, applied in order (COLLADA's convention).
	bool transformOf(const XMLElement* element, btTransform& out, bool& any)
	{
		out.setIdentity();
		any = false;
		for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
		{
			btTransform step;
			step.setIdentity();
			if (std::strcmp(child->Name(), "translate") == 0)
			{
				btVector3 offset;
				if (!vector(child, offset)) return false;
				step.setOrigin(offset * m_scale);
			}
			else if (std::strcmp(child->Name(), "rotate") == 0)
			{
				btScalar v[4] = {0, 0, 0, 0};
				if (!numbers(child, 4, v)) return false;
				const btVector3 axis(v[0], v[1], v[2]);
				if (v[3] != 0)
				{
					if (!(axis.length() > btScalar(1e-6))) return fail(child, "<rotate> has a zero axis");
					step.setRotation(btQuaternion(axis.normalized(), v[3] * SIMD_PI / 180));
				}
			}
			else if (std::strcmp(child->Name(), "matrix") == 0)
			{
				btScalar m[16] = {};
				if (!numbers(child, 16, m)) return false;
				const btMatrix3x3 basis(m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]);
				// Rigid bodies cannot be scaled or sheared: the rotation part must be orthonormal.
				const btMatrix3x3 error = basis * basis.transpose();
				bool rigid = m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1 && basis.determinant() > 0;
				for (int r = 0; r < 3; ++r)
					for (int c = 0; c < 3; ++c)
						rigid = rigid && btFabs(error[r][c] - (r == c ? 1 : 0)) < btScalar(1e-4);
				if (!rigid)
					return fail(child,
					            "<matrix> is not a rotation and translation (scale and shear are not supported)");
				step.setBasis(basis);
				step.setOrigin(btVector3(m[3], m[7], m[11]) * m_scale);
			}
			else if (std::strcmp(child->Name(), "scale") == 0 || std::strcmp(child->Name(), "skew") == 0 ||
			         std::strcmp(child->Name(), "lookat") == 0)
				return fail(child, std::string("<") + child->Name() + "> is not supported for rigid bodies");
			else
				continue;
			out = out * step;
			any = true;
		}
		return true;
	}

	bool readNodes(const XMLElement* root)
	{
		const XMLElement* library = root->FirstChildElement("library_visual_scenes");
		if (!library) return true;
		for (const XMLElement* scene = library->FirstChildElement("visual_scene"); scene;
		     scene = scene->NextSiblingElement("visual_scene"))
			if (!readNodeTree(scene, btTransform::getIdentity())) return false;
		return true;
	}

	bool readNodeTree(const XMLElement* parent, const btTransform& parentPose)
	{
		for (const XMLElement* node = parent->FirstChildElement("node"); node; node = node->NextSiblingElement("node"))
		{
			btTransform local;
			bool any;
			if (!transformOf(node, local, any)) return false;
			const btTransform pose = parentPose * local;
			if (const char* id = node->Attribute("id")) m_nodePoses[id] = pose;
			if (!readNodeTree(node, pose)) return false;
		}
		return true;
	}

	bool positions(const XMLElement* geometryKind, btAlignedObjectArray<btVector3>& points)
	{
		const XMLElement* vertices = geometryKind->FirstChildElement("vertices");
		if (!vertices) return fail(geometryKind, "the geometry has no <vertices>");
		const XMLElement* input = vertices->FirstChildElement("input");
		while (input && !(input->Attribute("semantic") && std::strcmp(input->Attribute("semantic"), "POSITION") == 0))
			input = input->NextSiblingElement("input");
		if (!input) return fail(vertices, "<vertices> has no POSITION input");
		const XMLElement* source = resolve(input, "source", "source");
		if (!source) return false;
		const XMLElement* array = source->FirstChildElement("float_array");
		if (!array) return fail(source, "the positions' <source> has no <float_array>");
		std::vector<btScalar> values;
		if (!numberList(array, values)) return false;
		if (array->IntAttribute("count", -1) != int(values.size()))
			return fail(array,
			            "<float_array>'s count does not match its " + std::to_string(values.size()) + " numbers");
		if (values.size() % 3 != 0 || values.empty()) return fail(array, "the positions are not whole x y z triples");
		for (std::size_t i = 0; i < values.size(); i += 3)
			points.push_back(btVector3(values[i], values[i + 1], values[i + 2]) * m_scale);
		return true;
	}

	bool geometryShape(const XMLElement* instance, bool dynamic, btCollisionShape*& shape)
	{
		const XMLElement* geometry = resolve(instance, "url", "geometry");
		if (!geometry) return false;
		if (const XMLElement* convex = geometry->FirstChildElement("convex_mesh"))
		{
			const XMLElement* of = convex;
			if (convex->Attribute("convex_hull_of"))
			{
				const XMLElement* other = resolve(convex, "convex_hull_of", "geometry");
				if (!other) return false;
				of = other->FirstChildElement("mesh") ? other->FirstChildElement("mesh")
				                                      : other->FirstChildElement("convex_mesh");
				if (!of) return fail(other, "the geometry named by convex_hull_of has no mesh");
			}
			btAlignedObjectArray<btVector3> points;
			if (!positions(of, points)) return false;
			if (points.size() < 4) return fail(convex, "a convex mesh needs at least 4 points");
			btConvexHullShape* hull = new btConvexHullShape(&points[0][0], points.size(), sizeof(btVector3));
			m_scene.shapes.emplace_back(hull);
			shape = hull;
			return true;
		}
		const XMLElement* mesh = geometry->FirstChildElement("mesh");
		if (!mesh) return fail(geometry, "the geometry is neither a <convex_mesh> nor a <mesh>");
		if (dynamic)
			return fail(instance, "a triangle mesh can only be static (make it a convex_mesh, or decompose it)");
		btAlignedObjectArray<btVector3> points;
		if (!positions(mesh, points)) return false;
		std::unique_ptr<btTriangleMesh> triangleMesh(new btTriangleMesh());
		for (int i = 0; i < points.size(); ++i) triangleMesh->findOrAddVertex(points[i], false);
		bool anyPrimitive = false;
		for (const XMLElement* primitive = mesh->FirstChildElement(); primitive;
		     primitive = primitive->NextSiblingElement())
		{
			const char* kind = primitive->Name();
			if (std::strcmp(kind, "triangles") != 0 && std::strcmp(kind, "polylist") != 0 &&
			    std::strcmp(kind, "polygons") != 0)
			{
				if (std::strcmp(kind, "lines") == 0 || std::strcmp(kind, "linestrips") == 0 ||
				    std::strcmp(kind, "trifans") == 0 || std::strcmp(kind, "tristrips") == 0)
					return fail(primitive, std::string("<") + kind + "> meshes are not read");
				continue;
			}
			anyPrimitive = true;
			if (!readPrimitive(primitive, points.size(), *triangleMesh)) return false;
		}
		if (!anyPrimitive) return fail(mesh, "the mesh has no <triangles>, <polylist> or <polygons>");
		btBvhTriangleMeshShape* meshShape = new btBvhTriangleMeshShape(triangleMesh.get(), true);
		m_scene.meshes.push_back(std::move(triangleMesh));
		m_scene.shapes.emplace_back(meshShape);
		shape = meshShape;
		return true;
	}

	// The stride of a primitive's <p> (its largest input offset plus one) and the VERTEX input's offset.
	bool primitiveLayout(const XMLElement* primitive, int& stride, int& vertexOffset)
	{
		stride = 1;
		vertexOffset = 0;
		for (const XMLElement* input = primitive->FirstChildElement("input"); input;
		     input = input->NextSiblingElement("input"))
		{
			const int offset = input->IntAttribute("offset", 0);
			if (offset < 0 || offset > 63) return fail(input, "an <input>'s offset must be from 0 to 63");
			stride = std::max(stride, offset + 1);
			if (input->Attribute("semantic") && std::strcmp(input->Attribute("semantic"), "VERTEX") == 0)
				vertexOffset = offset;
		}
		return true;
	}

	// Corners [first, first + corners) of a <p>'s indices as a triangle fan (right for convex polygons,
	// which is what modelling tools write as quads and n-gons).
	bool addFan(const XMLElement* p, const std::vector<btScalar>& indices, std::size_t first, std::size_t corners,
	            int stride, int vertexOffset, int pointCount, std::size_t polygon, btTriangleMesh& mesh)
	{
		int corner[3] = {0, 0, 0};
		for (std::size_t k = 0; k < corners; ++k)
		{
			const btScalar value = indices[(first + k) * std::size_t(stride) + std::size_t(vertexOffset)];
			if (value != std::floor(value) || value < 0 || value >= btScalar(pointCount))
				return fail(p, "polygon " + std::to_string(polygon) + " has an index out of range");
			corner[k < 2 ? k : 2] = int(value);
			if (k >= 2)
			{
				mesh.addTriangleIndices(corner[0], corner[1], corner[2]);
				corner[1] = corner[2];
			}
		}
		return true;
	}

	// A <triangles>, <polylist> (<vcount> corners per polygon) or <polygons> (one <p> per polygon) element,
	// triangulated into mesh.
	bool readPrimitive(const XMLElement* primitive, int pointCount, btTriangleMesh& mesh)
	{
		const std::string kind = primitive->Name();
		int stride, vertexOffset;
		if (!primitiveLayout(primitive, stride, vertexOffset)) return false;
		const int count = primitive->IntAttribute("count", -1);
		if (count < 1) return fail(primitive, "<" + kind + "> needs a positive count");
		std::vector<btScalar> indices;
		if (kind == "polygons")
		{
			if (primitive->FirstChildElement("ph")) return fail(primitive, "<polygons> with holes (<ph>) are not read");
			int polygon = 0;
			for (const XMLElement* p = primitive->FirstChildElement("p"); p; p = p->NextSiblingElement("p"), ++polygon)
			{
				if (!numberList(p, indices)) return false;
				if (indices.size() % std::size_t(stride) != 0 || indices.size() / std::size_t(stride) < 3)
					return fail(p, "a polygon needs whole groups of " + std::to_string(stride) +
					                   " indices, at least 3 corners");
				if (!addFan(p, indices, 0, indices.size() / std::size_t(stride), stride, vertexOffset, pointCount,
				            std::size_t(polygon), mesh))
					return false;
			}
			if (polygon != count) return fail(primitive, "<polygons>' count does not match its <p> elements");
			return true;
		}
		const XMLElement* p = primitive->FirstChildElement("p");
		if (!p) return fail(primitive, "<" + kind + "> has no <p>");
		if (!numberList(p, indices)) return false;
		std::vector<btScalar> corners;
		if (kind == "triangles")
		{
			// Checked before the corner list is made, so a huge count cannot ask for a huge allocation.
			if (std::size_t(count) * 3 * std::size_t(stride) != indices.size())
				return fail(p, "<triangles>' count does not match its indices");
			corners.assign(std::size_t(count), btScalar(3));
		}
		else
		{
			const XMLElement* vcount = primitive->FirstChildElement("vcount");
			if (!vcount) return fail(primitive, "<polylist> has no <vcount>");
			if (!numberList(vcount, corners)) return false;
			if (corners.size() != std::size_t(count))
				return fail(vcount, "<polylist>'s count does not match its <vcount>'s " +
				                        std::to_string(corners.size()) + " numbers");
		}
		std::size_t total = 0;
		for (const btScalar n : corners)
		{
			if (n != std::floor(n) || n < 3 || n > btScalar(1e6))
				return fail(p, "<vcount> needs whole numbers of at least 3 corners");
			total += std::size_t(n);
		}
		if (total * std::size_t(stride) != indices.size())
			return fail(p, "<" + kind + ">' count does not match its indices (" + std::to_string(total) +
			                   " corners of " + std::to_string(stride) + " indices expected, " +
			                   std::to_string(indices.size()) + " found)");
		std::size_t first = 0;
		for (std::size_t polygon = 0; polygon < corners.size(); ++polygon)
		{
			if (!addFan(p, indices, first, std::size_t(corners[polygon]), stride, vertexOffset, pointCount, polygon,
			            mesh))
				return false;
			first += std::size_t(corners[polygon]);
		}
		return true;
	}

	bool positive(const XMLElement* at, btScalar value, const char* what)
	{
		return value > 0 || fail(at, std::string(what) + " must be positive");
	}

	bool readShape(const XMLElement* element, bool dynamic, btCollisionShape*& shape, btTransform& local, bool& placed)
	{
		shape = nullptr;
		if (!transformOf(element, local, placed)) return false;
		for (const XMLElement* kind = element->FirstChildElement(); kind; kind = kind->NextSiblingElement())
		{
			const char* name = kind->Name();
			btCollisionShape* made = nullptr;
			if (std::strcmp(name, "box") == 0)
			{
				const XMLElement* half = kind->FirstChildElement("half_extents");
				btVector3 extents;
				if (!half) return fail(kind, "<box> has no <half_extents>");
				if (!vector(half, extents)) return false;
				if (!(extents.x() > 0 && extents.y() > 0 && extents.z() > 0))
					return fail(half, "half extents must be positive");
				made = new btBoxShape(extents * m_scale);
			}
			else if (std::strcmp(name, "sphere") == 0)
			{
				const XMLElement* radius = kind->FirstChildElement("radius");
				btScalar r = 0;
				if (!radius) return fail(kind, "<sphere> has no <radius>");
				if (!numbers(radius, 1, &r) || !positive(radius, r, "the radius")) return false;
				made = new btSphereShape(r * m_scale);
			}
			else if (std::strcmp(name, "plane") == 0)
			{
				const XMLElement* equation = kind->FirstChildElement("equation");
				btScalar e[4] = {0, 0, 0, 0};
				if (!equation) return fail(kind, "<plane> has no <equation>");
				if (!numbers(equation, 4, e)) return false;
				if (dynamic) return fail(kind, "a plane can only be static");
				btVector3 normal(e[0], e[1], e[2]);
				btScalar constant = -e[3] * m_scale;
				const btScalar length = normal.length();
				if (!(length > btScalar(1e-6))) return fail(equation, "the plane's normal is zero");
				if (btFabs(length - 1) > btScalar(1e-6))  // keep exact unit normals exact
				{
					normal /= length;
					constant /= length;
				}
				made = new btStaticPlaneShape(normal, constant);
			}
			else if (std::strcmp(name, "cylinder") == 0 || std::strcmp(name, "capsule") == 0)
			{
				const XMLElement* height = kind->FirstChildElement("height");
				const XMLElement* radius = kind->FirstChildElement("radius");
				btScalar h = 0, r[2] = {0, 0};
				if (!height || !radius) return fail(kind, std::string("<") + name + "> needs <height> and <radius>");
				if (!numbers(height, 1, &h) || !numbers(radius, 2, r)) return false;
				if (r[0] != r[1]) return fail(radius, "elliptic cylinders and capsules are not supported");
				if (!positive(radius, r[0], "the radius")) return false;
				if (!(h >= 0)) return fail(height, "the height must not be negative");
				if (std::strcmp(name, "cylinder") == 0)
					made = new btCylinderShape(btVector3(r[0], h / 2, r[0]) * m_scale);
				else
					made = new btCapsuleShape(r[0] * m_scale, h * m_scale);
			}
			else if (std::strcmp(name, "instance_geometry") == 0)
			{
				if (!geometryShape(kind, dynamic, shape)) return false;
				return true;
			}
			else if (std::strcmp(name, "tapered_cylinder") == 0 || std::strcmp(name, "tapered_capsule") == 0)
				return fail(kind, std::string("<") + name + "> is not supported");
			else
				continue;
			m_scene.shapes.emplace_back(made);
			shape = made;
			return true;
		}
		return fail(element, "<shape> holds no shape this reader knows");
	}

	bool readBody(const XMLElement* physicsModel, const XMLElement* instance)
	{
		const char* sid = instance->Attribute("body");
		if (!sid) return fail(instance, "<instance_rigid_body> has no body attribute");
		const XMLElement* rigidBody = physicsModel->FirstChildElement("rigid_body");
		while (rigidBody && !(rigidBody->Attribute("sid") && std::strcmp(rigidBody->Attribute("sid"), sid) == 0))
			rigidBody = rigidBody->NextSiblingElement("rigid_body");
		if (!rigidBody) return fail(instance, std::string("the physics model has no rigid body '") + sid + "'");
		const char* target = instance->Attribute("target");
		if (!target || target[0] != '#' || !m_nodePoses.count(target + 1))
			return fail(instance, std::string("the target '") + (target ? target : "") + "' names no node");
		btTransform pose = m_nodePoses[target + 1];
		if (m_turn) pose = btTransform(m_up * pose.getBasis(), m_up * pose.getOrigin());
		const XMLElement* common = rigidBody->FirstChildElement("technique_common");
		if (!common) return fail(rigidBody, "<rigid_body> has no <technique_common>");

		bool dynamic = true;
		if (const XMLElement* d = common->FirstChildElement("dynamic"))
			if (!boolean(d, dynamic)) return false;
		btScalar mass = 0;
		if (dynamic)
		{
			const XMLElement* m = common->FirstChildElement("mass");
			if (!m) return fail(common, "a dynamic body needs a <mass>");
			if (!numbers(m, 1, &mass) || !positive(m, mass, "a dynamic body's mass")) return false;
		}
		// Shapes: one without a placement is the body's shape; several, or a placed one, make a compound.
		std::vector<std::pair<btCollisionShape*, btTransform>> parts;
		bool anyPlaced = false;
		for (const XMLElement* s = common->FirstChildElement("shape"); s; s = s->NextSiblingElement("shape"))
		{
			btCollisionShape* shape;
			btTransform local;
			bool placed;
			if (!readShape(s, dynamic, shape, local, placed)) return false;
			anyPlaced = anyPlaced || placed;
			parts.emplace_back(shape, local);
		}
		if (parts.empty()) return fail(common, "the rigid body has no <shape>");
		// mass_frame: the centre of mass and principal axes in the body's (node's) frame. A Bullet body's frame
		// is its centre of mass, so a dynamic body's shapes move into that frame and its pose onto it; for a
		// static body it means nothing.
		btTransform massFrame = btTransform::getIdentity();
		if (const XMLElement* frame = common->FirstChildElement("mass_frame"))
		{
			bool any;
			if (!transformOf(frame, massFrame, any)) return false;
			if (!dynamic || !any) massFrame.setIdentity();
			if (dynamic && any)
			{
				const btTransform toCentre = massFrame.inverse();
				for (auto& part : parts) part.second = toCentre * part.second;
				anyPlaced = true;
			}
		}
		btCollisionShape* shape = parts[0].first;
		if (parts.size() > 1 || anyPlaced)
		{
			btCompoundShape* compound = new btCompoundShape();
			m_scene.shapes.emplace_back(compound);
			for (const auto& part : parts)
			{
				if (part.first->getShapeType() == STATIC_PLANE_PROXYTYPE ||
				    part.first->getShapeType() == TRIANGLE_MESH_SHAPE_PROXYTYPE)
					return fail(common, "planes and triangle meshes cannot be parts of a body of several shapes");
				compound->addChildShape(part.second, part.first);
			}
			shape = compound;
		}
		btVector3 inertia(0, 0, 0);
		if (dynamic)
		{
			if (const XMLElement* i = common->FirstChildElement("inertia"))
			{
				if (!vector(i, inertia)) return false;
				if (!(inertia.x() >= 0 && inertia.y() >= 0 && inertia.z() >= 0))
					return fail(i, "the inertia must not be negative");
				inertia *= m_scale * m_scale;  // mass times length squared
			}
			else
				shape->calculateLocalInertia(mass, inertia);
		}
		btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
		if (const XMLElement* material = common->FirstChildElement("instance_physics_material"))
		{
			const XMLElement* physicsMaterial = resolve(material, "url", "physics_material");
			if (!physicsMaterial) return false;
			if (const XMLElement* mc = physicsMaterial->FirstChildElement("technique_common"))
			{
				if (const XMLElement* f = mc->FirstChildElement("dynamic_friction"))
					if (!numbers(f, 1, &info.m_friction)) return false;
				if (const XMLElement* r = mc->FirstChildElement("restitution"))
					if (!numbers(r, 1, &info.m_restitution)) return false;
				if (!(info.m_friction >= 0) || !(info.m_restitution >= 0))
					return fail(mc, "friction and restitution must not be negative");
			}
		}
		info.m_startWorldTransform = massFrame == btTransform::getIdentity() ? pose : pose * massFrame;
		std::unique_ptr<btRigidBody> body(new btRigidBody(info));
		if (const XMLElement* ic = instance->FirstChildElement("technique_common"))
		{
			btVector3 velocity;
			if (const XMLElement* v = ic->FirstChildElement("velocity"))
			{
				if (!vector(v, velocity)) return false;
				body->setLinearVelocity(toWorld(velocity * m_scale));
			}
			if (const XMLElement* w = ic->FirstChildElement("angular_velocity"))
			{
				if (!vector(w, velocity)) return false;
				body->setAngularVelocity(toWorld(velocity * (SIMD_PI / 180)));  // COLLADA gives degrees per second
			}
		}
		// Caliber's exact radians, when the document came from Caliber's writer.
		if (const XMLElement* exact = caliberExtra(instance))
			if (const XMLElement* w = exact->FirstChildElement("angular_velocity_radians"))
			{
				btVector3 radians;
				if (!vector(w, radians)) return false;
				body->setAngularVelocity(toWorld(radians));
			}
		// A sid instanced twice cannot name one body for a joint.
		const auto known = m_instancedBodies.find(sid);
		if (known == m_instancedBodies.end())
			m_instancedBodies.emplace(sid, int(m_scene.bodies.size()));
		else
			known->second = -1;
		m_scene.bodies.push_back(std::move(body));
		m_massFrames.push_back(massFrame);
		m_scene.bodyNames.push_back(rigidBody->Attribute("name") ? rigidBody->Attribute("name") : sid);
		return true;
	}

	bool boolean(const XMLElement* element, bool& out)
	{
		const char* text = element->GetText() ? element->GetText() : "";
		if (std::strcmp(text, "true") != 0 && std::strcmp(text, "false") != 0)
			return fail(element, std::string("<") + element->Name() + "> must be true or false");
		out = std::strcmp(text, "true") == 0;
		return true;
	}

	// Caliber's <extra> of element, when there is one.
	static const XMLElement* caliberExtra(const XMLElement* element)
	{
		for (const XMLElement* extra = element->FirstChildElement("extra"); extra;
		     extra = extra->NextSiblingElement("extra"))
			for (const XMLElement* t = extra->FirstChildElement("technique"); t; t = t->NextSiblingElement("technique"))
				if (t->Attribute("profile") && std::strcmp(t->Attribute("profile"), "Caliber") == 0) return t;
		return nullptr;
	}

	bool exactFrame(const XMLElement* element, btTransform& out)
	{
		btScalar m[12] = {};
		if (!numbers(element, 12, m)) return false;
		out.setBasis(btMatrix3x3(m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]));
		out.setOrigin(btVector3(m[3], m[7], m[11]) * m_scale);
		return true;
	}

	// The body an attachment names, and the attachment's frame in that body.
	bool attachmentOf(const XMLElement* constraint, const char* name, btRigidBody*& body, btTransform& frame,
	                  btTransform& massFrame)
	{
		const XMLElement* element = constraint->FirstChildElement(name);
		if (!element) return fail(constraint, std::string("<rigid_constraint> has no <") + name + ">");
		const char* sid = element->Attribute("rigid_body");
		const auto found = sid ? m_instancedBodies.find(sid) : m_instancedBodies.end();
		if (found == m_instancedBodies.end())
			return fail(element, std::string("'") + (sid ? sid : "") + "' names no rigid body instanced in this scene");
		if (found->second < 0)
			return fail(element, std::string("the rigid body '") + sid + "' is instanced more than once");
		body = m_scene.bodies[std::size_t(found->second)].get();
		massFrame = m_massFrames[std::size_t(found->second)];
		bool any;
		return transformOf(element, frame, any);
	}

	bool readJoint(const XMLElement* physicsModel, const XMLElement* instance)
	{
		const char* sid = instance->Attribute("constraint");
		const XMLElement* constraint = physicsModel->FirstChildElement("rigid_constraint");
		while (sid && constraint &&
		       !(constraint->Attribute("sid") && std::strcmp(constraint->Attribute("sid"), sid) == 0))
			constraint = constraint->NextSiblingElement("rigid_constraint");
		if (!sid || !constraint)
			return fail(instance, std::string("the physics model has no rigid constraint '") + (sid ? sid : "") + "'");
		btRigidBody *bodyA, *bodyB;
		btTransform frameA, frameB;
		btTransform massFrameA, massFrameB;
		if (!attachmentOf(constraint, "ref_attachment", bodyA, frameA, massFrameA) ||
		    !attachmentOf(constraint, "attachment", bodyB, frameB, massFrameB))
			return false;
		if (bodyA == bodyB) return fail(constraint, "a joint needs two different bodies");
		// Bullet's defaults: every axis locked, enabled, the linked bodies still collide.
		btVector3 linearLower(0, 0, 0), linearUpper(0, 0, 0), angularLower(0, 0, 0), angularUpper(0, 0, 0);
		bool enabled = true, interpenetrate = false, referenceFrameA = true;
		if (const XMLElement* common = constraint->FirstChildElement("technique_common"))
		{
			if (const XMLElement* e = common->FirstChildElement("enabled"))
				if (!boolean(e, enabled)) return false;
			if (const XMLElement* e = common->FirstChildElement("interpenetrate"))
				if (!boolean(e, interpenetrate)) return false;
			if (const XMLElement* limits = common->FirstChildElement("limits"))
			{
				if (const XMLElement* angular = limits->FirstChildElement("swing_cone_and_twist"))
				{
					const XMLElement *lo = angular->FirstChildElement("min"), *hi = angular->FirstChildElement("max");
					if (lo && !vector(lo, angularLower)) return false;
					if (hi && !vector(hi, angularUpper)) return false;
					angularLower *= SIMD_PI / 180;  // COLLADA gives degrees
					angularUpper *= SIMD_PI / 180;
				}
				if (const XMLElement* linear = limits->FirstChildElement("linear"))
				{
					const XMLElement *lo = linear->FirstChildElement("min"), *hi = linear->FirstChildElement("max");
					if (lo && !vector(lo, linearLower)) return false;
					if (hi && !vector(hi, linearUpper)) return false;
					linearLower *= m_scale;
					linearUpper *= m_scale;
				}
			}
		}
		// Caliber's exact frames and angles, when the document came from Caliber's writer.
		if (const XMLElement* exact = caliberExtra(constraint))
		{
			if (const XMLElement* e = exact->FirstChildElement("frame_a"))
				if (!exactFrame(e, frameA)) return false;
			if (const XMLElement* e = exact->FirstChildElement("frame_b"))
				if (!exactFrame(e, frameB)) return false;
			if (const XMLElement* e = exact->FirstChildElement("angular_min_radians"))
				if (!vector(e, angularLower)) return false;
			if (const XMLElement* e = exact->FirstChildElement("angular_max_radians"))
				if (!vector(e, angularUpper)) return false;
			if (const XMLElement* e = exact->FirstChildElement("linear_reference_frame_a"))
				if (!boolean(e, referenceFrameA)) return false;
		}
		// Attachments are given in the bodies' frames; Bullet's joint frames are in their centre-of-mass frames.
		// (Only when there is a mass frame: multiplying by the identity could turn -0 into 0 in the round trip.)
		if (!(massFrameA == btTransform::getIdentity())) frameA = massFrameA.inverse() * frameA;
		if (!(massFrameB == btTransform::getIdentity())) frameB = massFrameB.inverse() * frameB;
		std::unique_ptr<btGeneric6DofConstraint> joint(
		    new btGeneric6DofConstraint(*bodyA, *bodyB, frameA, frameB, referenceFrameA));
		joint->setLinearLowerLimit(linearLower);
		joint->setLinearUpperLimit(linearUpper);
		joint->setAngularLowerLimit(angularLower);
		joint->setAngularUpperLimit(angularUpper);
		joint->setEnabled(enabled);
		m_scene.constraints.push_back(std::move(joint));
		m_scene.constraintNames.push_back(sid);
		m_scene.constraintsInterpenetrate.push_back(interpenetrate);
		return true;
	}

	ColladaPhysicsScene& m_scene;
	std::unordered_map<std::string, int> m_instancedBodies;  // body sid -> index, -1 when instanced twice
	tinyxml2::XMLDocument m_document;
	std::unordered_map<std::string, const XMLElement*> m_ids;
	std::vector<btTransform> m_massFrames;                     // per body: its centre-of-mass frame in its node's frame
	std::unordered_map<std::string, btTransform> m_nodePoses;  // in the document's axes, in metres
	btScalar m_scale = 1;
	btMatrix3x3 m_up = btMatrix3x3::getIdentity();
	bool m_turn = false;
};
}  // namespace

ColladaPhysicsScene::~ColladaPhysicsScene()
{
	if (m_world) removeFrom(*m_world);
	constraints.clear();  // joints before their bodies, bodies before the shapes and meshes they use
	bodies.clear();
	shapes.clear();
}

void ColladaPhysicsScene::addTo(btDiscreteDynamicsWorld& world)
{
	btAssert(!m_world && "ColladaPhysicsScene::addTo: the bodies are already in a world");
	if (m_world) return;
	m_world = &world;
	world.setGravity(gravity);
	for (auto& body : bodies) world.addRigidBody(body.get());
	for (std::size_t i = 0; i < constraints.size(); ++i)
		world.addConstraint(constraints[i].get(), constraintsInterpenetrate[i]);
}

void ColladaPhysicsScene::removeFrom(btDiscreteDynamicsWorld& world)
{
	if (m_world != &world) return;
	for (auto& constraint : constraints) world.removeConstraint(constraint.get());
	for (auto& body : bodies) world.removeRigidBody(body.get());
	m_world = nullptr;
}

bool importColladaPhysics(const char* text, std::size_t size, ColladaPhysicsScene& scene)
{
	btAssert(scene.bodies.empty() && "importColladaPhysics: the scene must be fresh");
	if (!scene.bodies.empty())
	{
		scene.error = "the scene already holds bodies";
		return false;
	}
	scene.error.clear();
	if (!text && size != 0)
	{
		btAssert(!"importColladaPhysics: null text with a non-zero size");
		scene.error = "null text with a non-zero size";
		return false;
	}
	if (size == 0)
	{
		scene.error = "line 0: the document is empty";
		return false;
	}
	Reader reader(scene);
	if (reader.run(text, size)) return true;
	const std::string error = scene.error;  // a failed import holds nothing
	scene.constraints.clear();
	scene.constraintNames.clear();
	scene.constraintsInterpenetrate.clear();
	scene.bodies.clear();
	scene.bodyNames.clear();
	scene.shapes.clear();
	scene.meshes.clear();
	scene.error = error;
	return false;
}

bool importColladaPhysicsFile(const char* path, ColladaPhysicsScene& scene)
{
	if (!path)
	{
		btAssert(!"importColladaPhysicsFile: null path");
		scene.error = "null path";
		return false;
	}
	std::FILE* file = std::fopen(path, "rb");
	if (!file)
	{
		scene.error = std::string("cannot open '") + path + "'";
		return false;
	}
	std::string text;
	char buffer[65536];
	std::size_t got;
	while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, got);
	std::fclose(file);
	return importColladaPhysics(text.data(), text.size(), scene);
}
}  // namespace caliber
