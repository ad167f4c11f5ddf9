// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef SOFT_BULLET_WORLD_IMPORTER_H
#define SOFT_BULLET_WORLD_IMPORTER_H

#include "btBulletWorldImporter.h"
#include "BulletSoftBody/btSoftBody.h"

class btSoftRigidDynamicsWorld;

/// Loads .bullet files with soft bodies: everything btBulletWorldImporter loads, then each soft body
/// (btSoftBodyFloatData: materials, nodes, links, faces, tetras, anchors, pose, configuration, clusters and
/// joints), added to the world given to the constructor (if any). Bullet 2.89 ships this only as a
/// demo class of its SerializeDemo; the name and calls follow it. A soft body whose data is inconsistent
/// (counts beyond its arrays, node indices out of range, non-finite numbers, pointers to the wrong kind
/// of chunk) is skipped with a warning; docs/serialization.md, "Soft bodies".
class btSoftBulletWorldImporter : public btBulletWorldImporter
{
public:
	/// world may be null: the bodies are then made with this importer's own btSoftBodyWorldInfo (keep the
	/// importer while they live) and added nowhere.
	btSoftBulletWorldImporter(btSoftRigidDynamicsWorld* world = 0);
	~btSoftBulletWorldImporter() override;

	/// The rigid content (btBulletWorldImporter), then the soft bodies and their joints.
	bool convertAllObjects(bParse::btBulletFile* bulletFile) override;
	/// Removes and deletes the soft bodies, then everything else.
	void deleteAllData() override;

	/// Soft bodies made by the loads so far, in the file's order.
	int getNumSoftBodies() const { return m_softBodies.size(); }
	/// Soft body index (0 when out of range).
	btSoftBody* getSoftBodyByIndex(int index) const;

protected:
	btSoftRigidDynamicsWorld* m_softRigidWorld;
	/// Used for the bodies when there is no world.
	btSoftBodyWorldInfo m_ownWorldInfo;
	btAlignedObjectArray<btSoftBody*> m_softBodies;
	/// A file body's cluster array (the target of a joint side naming its first cluster) to the body made.
	btHashMap<btHashPtr, btSoftBody*> m_clusterBodyMap;
	/// A file body's struct to the body made.
	btHashMap<btHashPtr, btSoftBody*> m_softBodyMap;
};

#endif
