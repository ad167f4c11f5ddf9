// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// COLLADA 1.4.1 physics export. The document is written as text (tinyxml2 reads it back); numbers use
// %.9g in single and %.17g in double precision, which read back bit for bit.
#include <cstdio>
#include <sstream>

#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"
#include "ColladaPhysics.h"

namespace caliber
{
namespace
{
std::string number(btScalar value)
{
	char buffer[40];
#ifdef BT_USE_DOUBLE_PRECISION
	std::snprintf(buffer, sizeof(buffer), "%.17g", double(value));
#else
	std::snprintf(buffer, sizeof(buffer), "%.9g", double(value));
#endif
	return buffer;
}

std::string vector3(const btVector3& v) { return number(v.x()) + " " + number(v.y()) + " " + number(v.z()); }

// A body's pose as COLLADA's row-major 4 x 4 matrix.
std::string matrix(const btTransform& t)
{
	std::string out;
	for (int row = 0; row < 3; ++row)
	{
		for (int column = 0; column < 3; ++column) out += number(t.getBasis()[row][column]) + " ";
		out += number(t.getOrigin()[row]) + " ";
	}
	return out + "0 0 0 1";
}

// A rotation as COLLADA's axis and angle in degrees.
std::string rotation(const btQuaternion& q)
{
	const btScalar angle = q.getAngle();
	if (angle == 0) return "1 0 0 0";
	return vector3(q.getAxis()) + " " + number(angle * btScalar(180) / SIMD_PI);
}

class Writer
{
public:
	explicit Writer(std::string& error) : m_error(error) {}

	// The <shape> element(s) of one body's shape into shapes; geometries it needs into m_geometries.
	bool writeShape(const btCollisionShape* shape, const btTransform* local, const std::string& where,
	                std::string& shapes)
	{
		std::string body;
		btQuaternion extraRotation = btQuaternion::getIdentity();
		switch (shape->getShapeType())
		{
			case BOX_SHAPE_PROXYTYPE:
			{
				const btBoxShape* box = static_cast<const btBoxShape*>(shape);
				body = "<box><half_extents>" + vector3(box->getHalfExtentsWithMargin()) + "</half_extents></box>";
				break;
			}
			case SPHERE_SHAPE_PROXYTYPE:
				body = "<sphere><radius>" + number(static_cast<const btSphereShape*>(shape)->getRadius()) +
				       "</radius></sphere>";
				break;
			case STATIC_PLANE_PROXYTYPE:
			{
				const btStaticPlaneShape* plane = static_cast<const btStaticPlaneShape*>(shape);
				// COLLADA's plane is a x + b y + c z + d = 0; Bullet's is normal . x = constant.
				body = "<plane><equation>" + vector3(plane->getPlaneNormal()) + " " +
				       number(-plane->getPlaneConstant()) + "</equation></plane>";
				break;
			}
			case CYLINDER_SHAPE_PROXYTYPE:
			{
				const btCylinderShape* cylinder = static_cast<const btCylinderShape*>(shape);
				const int axis = cylinder->getUpAxis();
				const btVector3 half = cylinder->getHalfExtentsWithMargin();
				const btScalar radius = half[(axis + 1) % 3];
				body = "<cylinder><height>" + number(2 * half[axis]) + "</height><radius>" + number(radius) + " " +
				       number(radius) + "</radius></cylinder>";
				extraRotation = towardsAxis(axis);
				break;
			}
			case CAPSULE_SHAPE_PROXYTYPE:
			{
				const btCapsuleShape* capsule = static_cast<const btCapsuleShape*>(shape);
				body = "<capsule><height>" + number(2 * capsule->getHalfHeight()) + "</height><radius>" +
				       number(capsule->getRadius()) + " " + number(capsule->getRadius()) + "</radius></capsule>";
				extraRotation = towardsAxis(capsule->getUpAxis());
				break;
			}
			case CONVEX_HULL_SHAPE_PROXYTYPE:
			{
				const btConvexHullShape* hull = static_cast<const btConvexHullShape*>(shape);
				const std::string id =
				    geometry("convex_mesh", hull->getUnscaledPoints(), hull->getNumPoints(), nullptr, 0);
				body = "<instance_geometry url=\"#" + id + "\"/>";
				break;
			}
			case TRIANGLE_MESH_SHAPE_PROXYTYPE:
			{
				std::string id;
				if (!meshGeometry(static_cast<const btBvhTriangleMeshShape*>(shape), where, id)) return false;
				body = "<instance_geometry url=\"#" + id + "\"/>";
				break;
			}
			case COMPOUND_SHAPE_PROXYTYPE:
			{
				if (local)
				{
					m_error = where + ": a compound inside a compound is not supported";
					return false;
				}
				const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
				for (int i = 0; i < compound->getNumChildShapes(); ++i)
					if (!writeShape(compound->getChildShape(i), &compound->getChildTransform(i), where, shapes))
						return false;
				return true;
			}
			default:
				m_error = where + ": shape type " + std::to_string(shape->getShapeType()) + " (" + shape->getName() +
				          ") has no COLLADA form here";
				return false;
		}
		shapes += "<shape>" + body;
		btTransform placement = local ? *local : btTransform::getIdentity();
		placement.setRotation(placement.getRotation() * extraRotation);
		if (placement.getOrigin() != btVector3(0, 0, 0))
			shapes += "<translate>" + vector3(placement.getOrigin()) + "</translate>";
		if (placement.getRotation().getAngle() != 0)
			shapes += "<rotate>" + rotation(placement.getRotation()) + "</rotate>";
		shapes += "</shape>";
		return true;
	}

	std::string m_geometries;

private:
	// COLLADA's cylinders and capsules run along y; this turns y onto the shape's axis.
	static btQuaternion towardsAxis(int axis)
	{
		if (axis == 0) return btQuaternion(btVector3(0, 0, 1), -SIMD_HALF_PI);
		if (axis == 2) return btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI);
		return btQuaternion::getIdentity();
	}

	std::string geometry(const char* kind, const btVector3* points, int count, const int* indices, int indexCount)
	{
		const std::string id = "geometry" + std::to_string(m_geometryCount++);
		std::string& g = m_geometries;
		g += "<geometry id=\"" + id + "\"><" + kind + "><source id=\"" + id + "-positions\"><float_array id=\"" + id +
		     "-array\" count=\"" + std::to_string(3 * count) + "\">";
		for (int i = 0; i < count; ++i) g += (i ? " " : "") + vector3(points[i]);
		g += "</float_array><technique_common><accessor source=\"#" + id + "-array\" count=\"" + std::to_string(count) +
		     "\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" "
		     "type=\"float\"/></accessor></technique_common></source><vertices id=\"" +
		     id + "-vertices\"><input semantic=\"POSITION\" source=\"#" + id + "-positions\"/></vertices>";
		if (indices)
		{
			g += "<triangles count=\"" + std::to_string(indexCount / 3) + "\"><input semantic=\"VERTEX\" source=\"#" +
			     id + "-vertices\" offset=\"0\"/><p>";
			for (int i = 0; i < indexCount; ++i) g += (i ? " " : "") + std::to_string(indices[i]);
			g += "</p></triangles>";
		}
		g += std::string("</") + kind + "></geometry>\n";
		return id;
	}

	bool meshGeometry(const btBvhTriangleMeshShape* shape, const std::string& where, std::string& id)
	{
		const btStridingMeshInterface* mesh = shape->getMeshInterface();
		btAlignedObjectArray<btVector3> points;
		std::vector<int> indices;
		for (int part = 0; part < mesh->getNumSubParts(); ++part)
		{
			const unsigned char *vertexBase, *indexBase;
			int numVertices, vertexStride, indexStride, numFaces;
			PHY_ScalarType vertexType, indexType;
			mesh->getLockedReadOnlyVertexIndexBase(&vertexBase, numVertices, vertexType, vertexStride, &indexBase,
			                                       indexStride, numFaces, indexType, part);
			const int first = points.size();
			for (int v = 0; v < numVertices; ++v)
			{
				const unsigned char* p = vertexBase + std::size_t(v) * vertexStride;
				if (vertexType == PHY_DOUBLE)
				{
					const double* d = reinterpret_cast<const double*>(p);
					points.push_back(btVector3(btScalar(d[0]), btScalar(d[1]), btScalar(d[2])) * mesh->getScaling());
				}
				else
				{
					const float* f = reinterpret_cast<const float*>(p);
					points.push_back(btVector3(btScalar(f[0]), btScalar(f[1]), btScalar(f[2])) * mesh->getScaling());
				}
			}
			for (int t = 0; t < numFaces; ++t)
			{
				const unsigned char* p = indexBase + std::size_t(t) * indexStride;
				for (int k = 0; k < 3; ++k)
				{
					int index = 0;
					if (indexType == PHY_INTEGER)
						index = reinterpret_cast<const int*>(p)[k];
					else if (indexType == PHY_SHORT)
						index = reinterpret_cast<const unsigned short*>(p)[k];
					else
						index = reinterpret_cast<const unsigned char*>(p)[k];
					indices.push_back(first + index);
				}
			}
			mesh->unLockReadOnlyVertexBase(part);
		}
		if (indices.empty())
		{
			m_error = where + ": the triangle mesh is empty";
			return false;
		}
		id = geometry("mesh", points.size() ? &points[0] : nullptr, points.size(), indices.data(), int(indices.size()));
		return true;
	}

	std::string& m_error;
	int m_geometryCount = 0;
};
// The 12 numbers of a frame for Caliber's <extra>: three rows of basis and origin.
std::string frame(const btTransform& t)
{
	std::string out;
	for (int row = 0; row < 3; ++row)
	{
		for (int column = 0; column < 3; ++column) out += number(t.getBasis()[row][column]) + " ";
		out += number(t.getOrigin()[row]) + (row < 2 ? " " : "");
	}
	return out;
}

std::string attachment(const char* element, int body, const btTransform& t)
{
	return std::string("<") + element + " rigid_body=\"body" + std::to_string(body) + "\"><translate>" +
	       vector3(t.getOrigin()) + "</translate><rotate>" + rotation(t.getRotation()) + "</rotate></" + element + ">";
}

bool writeJoints(const btDiscreteDynamicsWorld& world, std::string& joints, std::string& instances, std::string& error)
{
	const btCollisionObjectArray& objects = world.getCollisionObjectArray();
	const auto indexOf = [&objects](const btRigidBody& body)
	{
		for (int i = 0; i < objects.size(); ++i)
			if (objects[i] == &body) return i;
		return -1;
	};
	for (int c = 0; c < world.getNumConstraints(); ++c)
	{
		const btTypedConstraint* constraint = world.getConstraint(c);
		const std::string where = "joint " + std::to_string(c);
		if (constraint->getConstraintType() != D6_CONSTRAINT_TYPE)
		{
			error = where + ": only btGeneric6DofConstraint has a COLLADA form here (type " +
			        std::to_string(constraint->getConstraintType()) + ")";
			return false;
		}
		const btGeneric6DofConstraint* joint = static_cast<const btGeneric6DofConstraint*>(constraint);
		const int a = indexOf(joint->getRigidBodyA()), b = indexOf(joint->getRigidBodyB());
		if (a < 0 || b < 0)
		{
			error = where + ": joints to the world (or to bodies outside it) have no COLLADA form here";
			return false;
		}
		btVector3 linearLower, linearUpper, angularLower, angularUpper;
		joint->getLinearLowerLimit(linearLower);
		joint->getLinearUpperLimit(linearUpper);
		joint->getAngularLowerLimit(angularLower);
		joint->getAngularUpperLimit(angularUpper);
		const btScalar degrees = btScalar(180) / SIMD_PI;
		const bool interpenetrate = !joint->getRigidBodyA().checkCollideWith(&joint->getRigidBodyB());
		const std::string sid = "joint" + std::to_string(c);
		joints += "<rigid_constraint sid=\"" + sid + "\">" + attachment("ref_attachment", a, joint->getFrameOffsetA()) +
		          attachment("attachment", b, joint->getFrameOffsetB()) + "<technique_common><enabled>" +
		          (joint->isEnabled() ? "true" : "false") + "</enabled><interpenetrate>" +
		          (interpenetrate ? "true" : "false") + "</interpenetrate><limits><swing_cone_and_twist><min>" +
		          vector3(angularLower * degrees) + "</min><max>" + vector3(angularUpper * degrees) +
		          "</max></swing_cone_and_twist><linear><min>" + vector3(linearLower) + "</min><max>" +
		          vector3(linearUpper) + "</max></linear></limits></technique_common>" +
		          // Exact frames and angles for Caliber's reader (COLLADA's rotate and limits are in degrees).
		          "<extra><technique profile=\"Caliber\"><frame_a>" + frame(joint->getFrameOffsetA()) +
		          "</frame_a><frame_b>" + frame(joint->getFrameOffsetB()) + "</frame_b><angular_min_radians>" +
		          vector3(angularLower) + "</angular_min_radians><angular_max_radians>" + vector3(angularUpper) +
		          "</angular_max_radians><linear_reference_frame_a>" +
		          (joint->getUseLinearReferenceFrameA() ? "true" : "false") +
		          "</linear_reference_frame_a></technique></extra></rigid_constraint>\n";
		instances += "<instance_rigid_constraint constraint=\"" + sid + "\"/>\n";
	}
	return true;
}
}  // namespace

bool exportColladaPhysics(const btDiscreteDynamicsWorld& world, btScalar timeStep, std::string& out, std::string& error)
{
	out.clear();
	error.clear();
	Writer writer(error);
	std::string materials, bodies, nodes, instances;
	const btCollisionObjectArray& objects = world.getCollisionObjectArray();
	for (int i = 0; i < objects.size(); ++i)
	{
		const btRigidBody* body = btRigidBody::upcast(objects[i]);
		const std::string sid = "body" + std::to_string(i);
		if (!body)
		{
			error = "collision object " + std::to_string(i) + " is not a rigid body";
			return false;
		}
		const bool dynamic = body->getInvMass() > 0;
		std::string shapes;
		if (!writer.writeShape(body->getCollisionShape(), nullptr, sid, shapes)) return false;
		materials += "<physics_material id=\"material" + std::to_string(i) + "\"><technique_common><dynamic_friction>" +
		             number(body->getFriction()) + "</dynamic_friction><restitution>" + number(body->getRestitution()) +
		             "</restitution><static_friction>" + number(body->getFriction()) +
		             "</static_friction></technique_common></physics_material>\n";
		bodies += "<rigid_body sid=\"" + sid + "\"><technique_common><dynamic>" + (dynamic ? "true" : "false") +
		          "</dynamic><mass>" + number(dynamic ? 1 / body->getInvMass() : 0) + "</mass>";
		if (dynamic) bodies += "<inertia>" + vector3(body->getLocalInertia()) + "</inertia>";
		bodies += "<instance_physics_material url=\"#material" + std::to_string(i) + "\"/>" + shapes +
		          "</technique_common></rigid_body>\n";
		nodes += "<node id=\"node" + std::to_string(i) + "\"><matrix>" + matrix(body->getCenterOfMassTransform()) +
		         "</matrix></node>\n";
		instances += "<instance_rigid_body body=\"" + sid + "\" target=\"#node" + std::to_string(i) +
		             "\"><technique_common><angular_velocity>" + vector3(body->getAngularVelocity() * (180 / SIMD_PI)) +
		             "</angular_velocity><velocity>" + vector3(body->getLinearVelocity()) +
		             "</velocity></technique_common>"
		             // COLLADA's degrees per second do not convert back bit for bit; Caliber's reader takes this.
		             "<extra><technique profile=\"Caliber\"><angular_velocity_radians>" +
		             vector3(body->getAngularVelocity()) +
		             "</angular_velocity_radians></technique></extra></instance_rigid_body>\n";
	}
	std::string joints, jointInstances;
	if (!writeJoints(world, joints, jointInstances, error)) return false;
	bodies += joints;
	instances += jointInstances;
	out =
	    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
	    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
	    "<asset><contributor><authoring_tool>Caliber ColladaConverter</authoring_tool></contributor>"
	    "<unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
	    "<library_geometries>\n" +
	    writer.m_geometries + "</library_geometries>\n<library_physics_materials>\n" + materials +
	    "</library_physics_materials>\n<library_physics_models>\n<physics_model id=\"model\">\n" + bodies +
	    "</physics_model>\n</library_physics_models>\n<library_physics_scenes>\n<physics_scene id=\"scene\">\n"
	    "<instance_physics_model url=\"#model\">\n" +
	    instances + "</instance_physics_model>\n<technique_common><gravity>" + vector3(world.getGravity()) +
	    "</gravity><time_step>" + number(timeStep) +
	    "</time_step></technique_common>\n</physics_scene>\n</library_physics_scenes>\n"
	    "<library_visual_scenes>\n<visual_scene id=\"visual\">\n" +
	    nodes +
	    "</visual_scene>\n</library_visual_scenes>\n<scene><instance_physics_scene url=\"#scene\"/>"
	    "<instance_visual_scene url=\"#visual\"/></scene>\n</COLLADA>\n";
	return true;
}
}  // namespace caliber
