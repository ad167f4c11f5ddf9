// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Soft bodies in .bullet files: btSoftRigidDynamicsWorld::serialize writes btSoftBodyFloatData with its
// parts, btSoftBulletWorldImporter reads them back. The layout is single precision in every build, so
// each field read back must equal the original rounded to float (exact in a float build).
#include <gtest/gtest.h>

#include <stddef.h>

#include "BulletSoftBody/SoftBodyTestUtil.h"
#include "BulletSoftBody/btSoftBodyData.h"
#include "Serialize/SerializeTestUtil.h"
#include "btBulletFile.h"
#include "btBulletSoftBodyCommon.h"
#include "btSoftBulletWorldImporter.h"

using namespace caliber_test;

namespace
{
using caliber::isFinite;

// SoftTestWorld (tests/BulletSoftBody/SoftBodyTestUtil.h) owns the world's parts, shapes, rigid bodies and
// soft bodies; objects an importer made are the importer's: deleteAllData before the world goes.

btScalar f(btScalar x) { return btScalar(float(x)); }
void expectVec(const btVector3& original, const btVector3& read, const char* what)
{
	for (int i = 0; i < 3; ++i) EXPECT_EQ(f(original[i]), read[i]) << what << " [" << i << "]";
}
void expectMat(const btMatrix3x3& original, const btMatrix3x3& read, const char* what)
{
	for (int r = 0; r < 3; ++r) expectVec(original[r], read[r], what);
}

// A soft world with everything a soft body file holds: two materials, links with bending links, faces,
// tetras, anchors to a rigid box, a pose, clusters and a linear and an angular joint, every config field
// set to a distinct value, stepped a few times so that velocities, forces and cluster state are not zero.
struct Scene
{
	SoftTestWorld w;
	btRigidBody* box = 0;
	btSoftBody* cloth = 0;
	btSoftBody* block = 0;

	Scene()
	{
		w.addGround();
		box = w.addRigid(1, btVector3(0, 3, 0), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
		cloth = w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-1, 4, -1), btVector3(1, 4, -1),
		                                                 btVector3(-1, 4, 1), btVector3(1, 4, 1), 5, 5, 0, true));
		btSoftBody::Material* soft = cloth->appendMaterial();
		soft->m_kLST = btScalar(0.37);
		soft->m_kAST = btScalar(0.21);
		soft->m_kVST = btScalar(0.77);
		soft->m_flags = 0;
		cloth->generateBendingConstraints(2, soft);
		cloth->setTotalMass(2);
		cloth->appendAnchor(0, box);
		cloth->appendAnchor(4, box, btVector3(0.1, 0.2, 0.3));
		btSoftBody::Config& c = cloth->m_cfg;
		c.aeromodel = btSoftBody::eAeroModel::F_TwoSided;
		c.kVCF = 0.9;
		c.kDP = 0.01;
		c.kDG = 0.02;
		c.kLF = 0.03;
		c.kPR = 0.04;
		c.kVC = 0.05;
		c.kDF = 0.31;
		c.kMT = 0.06;
		c.kCHR = 0.91;
		c.kKHR = 0.11;
		c.kSHR = 0.92;
		c.kAHR = 0.71;
		c.kSRHR_CL = 0.12;
		c.kSKHR_CL = 0.93;
		c.kSSHR_CL = 0.51;
		c.kSR_SPLT_CL = 0.52;
		c.kSK_SPLT_CL = 0.53;
		c.kSS_SPLT_CL = 0.54;
		c.maxvolume = 1.1;
		c.timescale = 1.2;
		c.viterations = 1;
		c.piterations = 3;
		c.diterations = 2;
		c.citerations = 5;
		c.collisions = btSoftBody::fCollision::SDF_RS | btSoftBody::fCollision::VF_SS;
		cloth->setPose(true, true);

		block = w.addSoft(btSoftBodyHelpers::CreateFromTetGenData(w.info(), kEle, 0, kNode, false, true, true));
		block->translate(btVector3(3, 1, 0));
		block->setVolumeMass(1);
		block->m_cfg.collisions = btSoftBody::fCollision::CL_RS;
		block->generateClusters(2);
		btSoftBody::LJoint::Specs ls;
		ls.position = btVector3(3, 2, 0);
		ls.erp = 0.4;
		block->appendLinearJoint(ls, block->m_clusters[0], btSoftBody::Body(box));
		btSoftBody::AJoint::Specs as;
		as.axis = btVector3(0, 1, 0);
		as.erp = 0.3;
		block->appendAngularJoint(as, btSoftBody::Body());
		w.step(5);
		cloth->addForce(btVector3(0.5, 1.5, -0.25));
	}

	static const char* const kNode;
	static const char* const kEle;
};
// A cube of five tetras (TetGen's node and element formats).
const char* const Scene::kNode = "8 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 1 1 0\n4 0 0 1\n5 1 0 1\n6 0 1 1\n7 1 1 1\n";
const char* const Scene::kEle = "5 4 0\n0 0 1 2 4\n1 1 3 2 7\n2 1 4 5 7\n3 2 6 4 7\n4 1 2 4 7\n";

std::vector<char> writeWorld(btSoftRigidDynamicsWorld& world)
{
	btDefaultSerializer s;
	world.serialize(&s);
	return bytesOf(s);
}

void expectSameBody(const btSoftBody& a, const btSoftBody& b)
{
	ASSERT_EQ(a.m_materials.size(), b.m_materials.size());
	for (int i = 0; i < a.m_materials.size(); ++i)
	{
		EXPECT_EQ(f(a.m_materials[i]->m_kLST), b.m_materials[i]->m_kLST);
		EXPECT_EQ(f(a.m_materials[i]->m_kAST), b.m_materials[i]->m_kAST);
		EXPECT_EQ(f(a.m_materials[i]->m_kVST), b.m_materials[i]->m_kVST);
		EXPECT_EQ(a.m_materials[i]->m_flags, b.m_materials[i]->m_flags);
	}
	auto matIndex = [](const btSoftBody& s, const btSoftBody::Material* m)
	{ return s.m_materials.findLinearSearch(const_cast<btSoftBody::Material*>(m)); };
	ASSERT_EQ(a.m_nodes.size(), b.m_nodes.size());
	for (int i = 0; i < a.m_nodes.size(); ++i)
	{
		const btSoftBody::Node &p = a.m_nodes[i], &q = b.m_nodes[i];
		expectVec(p.m_x, q.m_x, "m_x");
		expectVec(p.m_q, q.m_q, "m_q");
		expectVec(p.m_v, q.m_v, "m_v");
		expectVec(p.m_f, q.m_f, "m_f");
		expectVec(p.m_n, q.m_n, "m_n");
		EXPECT_EQ(f(p.m_im), q.m_im);
		EXPECT_EQ(f(p.m_area), q.m_area);
		EXPECT_EQ(p.m_battach, q.m_battach);
		EXPECT_EQ(matIndex(a, p.m_material), matIndex(b, q.m_material));
	}
	ASSERT_EQ(a.m_links.size(), b.m_links.size());
	for (int i = 0; i < a.m_links.size(); ++i)
	{
		const btSoftBody::Link &p = a.m_links[i], &q = b.m_links[i];
		for (int j = 0; j < 2; ++j) EXPECT_EQ(p.m_n[j] - &a.m_nodes[0], q.m_n[j] - &b.m_nodes[0]);
		EXPECT_EQ(f(p.m_rl), q.m_rl);
		EXPECT_EQ(p.m_bbending, q.m_bbending);
		EXPECT_EQ(matIndex(a, p.m_material), matIndex(b, q.m_material));
	}
	ASSERT_EQ(a.m_faces.size(), b.m_faces.size());
	for (int i = 0; i < a.m_faces.size(); ++i)
	{
		const btSoftBody::Face &p = a.m_faces[i], &q = b.m_faces[i];
		for (int j = 0; j < 3; ++j) EXPECT_EQ(p.m_n[j] - &a.m_nodes[0], q.m_n[j] - &b.m_nodes[0]);
		expectVec(p.m_normal, q.m_normal, "face normal");
		EXPECT_EQ(f(p.m_ra), q.m_ra);
		EXPECT_EQ(matIndex(a, p.m_material), matIndex(b, q.m_material));
	}
	ASSERT_EQ(a.m_tetras.size(), b.m_tetras.size());
	for (int i = 0; i < a.m_tetras.size(); ++i)
	{
		const btSoftBody::Tetra &p = a.m_tetras[i], &q = b.m_tetras[i];
		for (int j = 0; j < 4; ++j)
		{
			EXPECT_EQ(p.m_n[j] - &a.m_nodes[0], q.m_n[j] - &b.m_nodes[0]);
			expectVec(p.m_c0[j], q.m_c0[j], "tetra m_c0");
		}
		EXPECT_EQ(f(p.m_rv), q.m_rv);
		EXPECT_EQ(f(p.m_c1), q.m_c1);
		EXPECT_EQ(f(p.m_c2), q.m_c2);
	}
	ASSERT_EQ(a.m_anchors.size(), b.m_anchors.size());
	for (int i = 0; i < a.m_anchors.size(); ++i)
	{
		const btSoftBody::Anchor &p = a.m_anchors[i], &q = b.m_anchors[i];
		EXPECT_EQ(p.m_node - &a.m_nodes[0], q.m_node - &b.m_nodes[0]);
		expectVec(p.m_local, q.m_local, "anchor m_local");
		expectMat(p.m_c0, q.m_c0, "anchor m_c0");
		expectVec(p.m_c1, q.m_c1, "anchor m_c1");
		EXPECT_EQ(f(p.m_c2), q.m_c2);
		ASSERT_NE(q.m_body, nullptr);
		// Rigid bodies are written in the build's precision: the anchored body comes back exactly.
		EXPECT_EQ(p.m_body->getWorldTransform().getOrigin(), q.m_body->getWorldTransform().getOrigin());
	}
	const btSoftBody::Config &c = a.m_cfg, &d = b.m_cfg;
	EXPECT_EQ(c.aeromodel, d.aeromodel);
	const btScalar ca[] = {c.kVCF,     c.kDP,         c.kDG,         c.kLF,         c.kPR,       c.kVC,      c.kDF,
	                       c.kMT,      c.kCHR,        c.kKHR,        c.kSHR,        c.kAHR,      c.kSRHR_CL, c.kSKHR_CL,
	                       c.kSSHR_CL, c.kSR_SPLT_CL, c.kSK_SPLT_CL, c.kSS_SPLT_CL, c.maxvolume, c.timescale};
	const btScalar da[] = {d.kVCF,     d.kDP,         d.kDG,         d.kLF,         d.kPR,       d.kVC,      d.kDF,
	                       d.kMT,      d.kCHR,        d.kKHR,        d.kSHR,        d.kAHR,      d.kSRHR_CL, d.kSKHR_CL,
	                       d.kSSHR_CL, d.kSR_SPLT_CL, d.kSK_SPLT_CL, d.kSS_SPLT_CL, d.maxvolume, d.timescale};
	for (size_t i = 0; i < sizeof(ca) / sizeof(ca[0]); ++i) EXPECT_EQ(f(ca[i]), da[i]) << "config field " << i;
	EXPECT_EQ(c.viterations, d.viterations);
	EXPECT_EQ(c.piterations, d.piterations);
	EXPECT_EQ(c.diterations, d.diterations);
	EXPECT_EQ(c.citerations, d.citerations);
	EXPECT_EQ(c.collisions, d.collisions);
	const btSoftBody::Pose &p = a.m_pose, &q = b.m_pose;
	EXPECT_EQ(p.m_bvolume, q.m_bvolume);
	EXPECT_EQ(p.m_bframe, q.m_bframe);
	EXPECT_EQ(f(p.m_volume), q.m_volume);
	expectVec(p.m_com, q.m_com, "pose com");
	expectMat(p.m_rot, q.m_rot, "pose rot");
	expectMat(p.m_scl, q.m_scl, "pose scl");
	expectMat(p.m_aqq, q.m_aqq, "pose aqq");
	ASSERT_EQ(p.m_pos.size(), q.m_pos.size());
	for (int i = 0; i < p.m_pos.size(); ++i) expectVec(p.m_pos[i], q.m_pos[i], "pose pos");
	ASSERT_EQ(p.m_wgh.size(), q.m_wgh.size());
	for (int i = 0; i < p.m_wgh.size(); ++i) EXPECT_EQ(f(p.m_wgh[i]), q.m_wgh[i]);
	ASSERT_EQ(a.m_clusters.size(), b.m_clusters.size());
	for (int i = 0; i < a.m_clusters.size(); ++i)
	{
		const btSoftBody::Cluster &x = *a.m_clusters[i], &y = *b.m_clusters[i];
		ASSERT_EQ(x.m_nodes.size(), y.m_nodes.size());
		for (int j = 0; j < x.m_nodes.size(); ++j)
		{
			EXPECT_EQ(x.m_nodes[j] - &a.m_nodes[0], y.m_nodes[j] - &b.m_nodes[0]);
			EXPECT_EQ(f(x.m_masses[j]), y.m_masses[j]);
		}
		ASSERT_EQ(x.m_framerefs.size(), y.m_framerefs.size());
		for (int j = 0; j < x.m_framerefs.size(); ++j) expectVec(x.m_framerefs[j], y.m_framerefs[j], "framerefs");
		expectMat(x.m_framexform.getBasis(), y.m_framexform.getBasis(), "cluster frame");
		expectVec(x.m_framexform.getOrigin(), y.m_framexform.getOrigin(), "cluster frame origin");
		expectMat(x.m_locii, y.m_locii, "m_locii");
		expectMat(x.m_invwi, y.m_invwi, "m_invwi");
		expectVec(x.m_com, y.m_com, "cluster com");
		expectVec(x.m_lv, y.m_lv, "cluster lv");
		expectVec(x.m_av, y.m_av, "cluster av");
		for (int j = 0; j < 2; ++j)
		{
			expectVec(x.m_vimpulses[j], y.m_vimpulses[j], "vimpulses");
			expectVec(x.m_dimpulses[j], y.m_dimpulses[j], "dimpulses");
		}
		const btScalar xs[] = {x.m_idmass,
		                       x.m_imass,
		                       x.m_ndamping,
		                       x.m_ldamping,
		                       x.m_adamping,
		                       x.m_matching,
		                       x.m_maxSelfCollisionImpulse,
		                       x.m_selfCollisionImpulseFactor};
		const btScalar ys[] = {y.m_idmass,
		                       y.m_imass,
		                       y.m_ndamping,
		                       y.m_ldamping,
		                       y.m_adamping,
		                       y.m_matching,
		                       y.m_maxSelfCollisionImpulse,
		                       y.m_selfCollisionImpulseFactor};
		for (size_t k = 0; k < sizeof(xs) / sizeof(xs[0]); ++k) EXPECT_EQ(f(xs[k]), ys[k]) << "cluster field " << k;
		EXPECT_EQ(x.m_nvimpulses, y.m_nvimpulses);
		EXPECT_EQ(x.m_ndimpulses, y.m_ndimpulses);
		EXPECT_EQ(x.m_containsAnchor, y.m_containsAnchor);
		EXPECT_EQ(x.m_collide, y.m_collide);
		EXPECT_EQ(x.m_clusterIndex, y.m_clusterIndex);
	}
	ASSERT_EQ(a.m_clusterConnectivity.size(), b.m_clusterConnectivity.size());
	for (int i = 0; i < a.m_clusterConnectivity.size(); ++i)
		EXPECT_EQ(a.m_clusterConnectivity[i], b.m_clusterConnectivity[i]);
	ASSERT_EQ(a.m_joints.size(), b.m_joints.size());
	for (int i = 0; i < a.m_joints.size(); ++i)
	{
		const btSoftBody::Joint &x = *a.m_joints[i], &y = *b.m_joints[i];
		EXPECT_EQ(x.Type(), y.Type());
		expectVec(x.m_refs[0], y.m_refs[0], "joint ref 0");
		expectVec(x.m_refs[1], y.m_refs[1], "joint ref 1");
		EXPECT_EQ(f(x.m_erp), y.m_erp);
		EXPECT_EQ(f(x.m_cfm), y.m_cfm);
		EXPECT_EQ(f(x.m_split), y.m_split);
		EXPECT_EQ(x.m_delete, y.m_delete);
		EXPECT_EQ(x.m_bodies[0].m_soft != 0, y.m_bodies[0].m_soft != 0);
		EXPECT_EQ(x.m_bodies[1].m_soft != 0, y.m_bodies[1].m_soft != 0);
		EXPECT_EQ(x.m_bodies[1].m_rigid != 0, y.m_bodies[1].m_rigid != 0);
	}
	expectVec(a.getWorldTransform().getOrigin(), b.getWorldTransform().getOrigin(), "world transform");
	EXPECT_EQ(f(a.getFriction()), b.getFriction());
	EXPECT_EQ(a.getActivationState(), b.getActivationState());
}
}  // namespace

TEST(SoftBodyFile, EveryFieldReadsBackAsWrittenInSinglePrecision)
{
	Scene scene;
	const std::vector<char> file = writeWorld(scene.w.world());
	SoftTestWorld other;
	btSoftBulletWorldImporter importer(&other.world());
	std::vector<char> copy = file;
	ASSERT_TRUE(importer.loadFileFromMemory(copy.data(), int(copy.size())));
	ASSERT_EQ(importer.getNumSoftBodies(), 2);
	EXPECT_EQ(importer.getNumRigidBodies(), 2);
	EXPECT_EQ(other.world().getSoftBodyArray().size(), 2);
	expectSameBody(*scene.cloth, *importer.getSoftBodyByIndex(0));
	expectSameBody(*scene.block, *importer.getSoftBodyByIndex(1));
	// The imported world steps (no NaN, the cloth stays near the original).
	other.step(10);
	scene.w.step(10);
	for (int i = 0; i < scene.cloth->m_nodes.size(); ++i)
		EXPECT_TRUE(isFinite(importer.getSoftBodyByIndex(0)->m_nodes[i].m_x));
	importer.deleteAllData();
	EXPECT_EQ(other.world().getSoftBodyArray().size(), 0);
}

TEST(SoftBodyFile, WriterUsesBulletStructNamesAndTheSoftBodyChunkCode)
{
	Scene scene;
	const std::vector<char> file = writeWorld(scene.w.world());
	const std::vector<ChunkAt> chunks = walkChunks(file);
	int soft = 0, materials = 0;
	for (const ChunkAt& c : chunks)
	{
		if (c.code == BT_SOFTBODY_CODE)
		{
			++soft;
			EXPECT_EQ(c.length, int(sizeof(btSoftBodyFloatData)));
		}
		if (c.code == BT_SBMATERIAL_CODE) ++materials;
	}
	EXPECT_EQ(soft, 2);
	EXPECT_EQ(materials, 3);  // the cloth's two, the block's one
	// The DNA knows every soft struct by Bullet's name.
	for (const char* name : {"btSoftBodyFloatData", "SoftBodyNodeData", "SoftBodyLinkData", "SoftBodyFaceData",
	                         "SoftBodyTetraData", "SoftRigidAnchorData", "SoftBodyConfigData", "SoftBodyPoseData",
	                         "SoftBodyClusterData", "btSoftBodyJointData", "SoftBodyMaterialData"})
	{
		const std::string dna(btDefaultSerializer::getMemoryDna(),
		                      size_t(btDefaultSerializer::getMemoryDnaSizeInBytes()));
		EXPECT_NE(dna.find(std::string(name) + '\0'), std::string::npos) << name;
	}
}

TEST(SoftBodyFile, ClothSavedBeforeItsFirstStepStepsBitIdenticallyAfterLoading)
{
	// Before the first step every derived quantity is built from what the file holds, so a float build
	// reproduces the trajectory bit for bit; a double build rounds the file's numbers to float.
	SoftTestWorld a;
	a.addGround();
	btSoftBody* cloth = a.addSoft(btSoftBodyHelpers::CreatePatch(
	    a.info(), btVector3(-1, 2, -1), btVector3(1, 2, -1), btVector3(-1, 2, 1), btVector3(1, 2, 1), 6, 6, 1, true));
	cloth->setTotalMass(1);
	const std::vector<char> file = writeWorld(a.world());
	SoftTestWorld b;
	btSoftBulletWorldImporter importer(&b.world());
	std::vector<char> copy = file;
	ASSERT_TRUE(importer.loadFileFromMemory(copy.data(), int(copy.size())));
	ASSERT_EQ(importer.getNumSoftBodies(), 1);
	btSoftBody* read = importer.getSoftBodyByIndex(0);
#ifdef BT_USE_DOUBLE_PRECISION
	// The file rounded the start to float (grid points 0.4 m apart: a relative 6e-8 at most); 30 steps of free
	// fall (0.5 s, 1.25 m: no contact yet) carry that rounding unchanged, so 1e-6 m bounds it.
	a.step(30);
	b.step(30);
	for (int i = 0; i < cloth->m_nodes.size(); ++i)
		for (int k = 0; k < 3; ++k) EXPECT_NEAR(cloth->m_nodes[i].m_x[k], read->m_nodes[i].m_x[k], 1e-6);
#else
	a.step(90);
	b.step(90);
	for (int i = 0; i < cloth->m_nodes.size(); ++i)
	{
		EXPECT_EQ(cloth->m_nodes[i].m_x, read->m_nodes[i].m_x) << "node " << i;
		EXPECT_EQ(cloth->m_nodes[i].m_v, read->m_nodes[i].m_v) << "node " << i;
	}
#endif
	importer.deleteAllData();
}

namespace
{
// The file with one field of the first soft body's struct (or of an array chunk) changed.
struct Damaged
{
	std::vector<char> file;
	std::vector<ChunkAt> chunks;
	explicit Damaged(std::vector<char> f) : file(std::move(f)), chunks(walkChunks(file)) {}
	char* softBody() { return &file[findChunk(chunks, BT_SOFTBODY_CODE)->data]; }
	template <class T>
	void set(size_t offset, T value)
	{
		memcpy(softBody() + offset, &value, sizeof(T));
	}
	// Loads into a fresh world; returns how many soft bodies were made.
	int load(WarningLog& log)
	{
		SoftTestWorld w;
		btSoftBulletWorldImporter importer(&w.world());
		importer.loadFileFromMemory(file.data(), int(file.size()));
		const int n = importer.getNumSoftBodies();
		for (int i = 0; i < n; ++i)
			for (int j = 0; j < importer.getSoftBodyByIndex(i)->m_nodes.size(); ++j)
				EXPECT_TRUE(isFinite(importer.getSoftBodyByIndex(i)->m_nodes[j].m_x));
		w.step(2);
		importer.deleteAllData();
		(void)log;
		return n;
	}
};
}  // namespace

TEST(SoftBodyFile, DamagedCountsIndicesAndNumbersSkipTheBodyWithAWarning)
{
	Scene scene;
	const std::vector<char> file = writeWorld(scene.w.world());
	{
		Damaged d(file);
		WarningLog log;
		EXPECT_EQ(d.load(log), 2);
		EXPECT_FALSE(log.contains("btSoftBulletWorldImporter")) << log.all();
	}
	struct Case
	{
		const char* what;
		size_t offset;
		int value;
		const char* message;
	};
	const Case cases[] = {
	    {"node count beyond the array", offsetof(btSoftBodyFloatData, m_numNodes), 1000000, "node array"},
	    {"negative link count", offsetof(btSoftBodyFloatData, m_numLinks), -3, "link array"},
	    {"face count beyond the array", offsetof(btSoftBodyFloatData, m_numFaces), 1 << 30, "face array"},
	    {"material count beyond the list", offsetof(btSoftBodyFloatData, m_numMaterials), 7, "material"},
	    {"anchor count beyond the array", offsetof(btSoftBodyFloatData, m_numAnchors), 99, "anchor array"},
	};
	for (const Case& c : cases)
	{
		Damaged d(file);
		d.set(c.offset, c.value);
		WarningLog log;
		EXPECT_EQ(d.load(log), 1) << c.what;
		EXPECT_TRUE(log.contains(c.message)) << c.what << ": " << log.all();
	}
	{
		// A non-finite config value.
		Damaged d(file);
		d.set(offsetof(btSoftBodyFloatData, m_config) + offsetof(SoftBodyConfigData, m_drag), float(NAN));
		WarningLog log;
		EXPECT_EQ(d.load(log), 1);
		EXPECT_TRUE(log.contains("non-finite")) << log.all();
	}
	{
		// A link whose node index is out of range: the link array is the first SoftBodyLinkData chunk.
		Damaged d(file);
		const ChunkAt* links = 0;
		for (const ChunkAt& c : d.chunks)
			if (c.code == BT_ARRAY_CODE && c.length == int(sizeof(SoftBodyLinkData)) * c.number && c.number > 40)
			{
				links = &c;
				break;
			}
		ASSERT_NE(links, nullptr);
		const int bad = 12345;
		memcpy(&d.file[links->data + offsetof(SoftBodyLinkData, m_nodeIndices)], &bad, sizeof(int));
		WarningLog log;
		EXPECT_EQ(d.load(log), 1);
		EXPECT_TRUE(log.contains("bad node indices")) << log.all();
	}
	{
		// The node array pointer names the link array: wrong struct.
		Damaged d(file);
		uint64_t linksId = 0, nodesId = 0;
		memcpy(&nodesId, d.softBody() + offsetof(btSoftBodyFloatData, m_nodes), sizeof(void*));
		memcpy(&linksId, d.softBody() + offsetof(btSoftBodyFloatData, m_links), sizeof(void*));
		ASSERT_NE(nodesId, linksId);
		memcpy(d.softBody() + offsetof(btSoftBodyFloatData, m_nodes), &linksId, sizeof(void*));
		WarningLog log;
		EXPECT_EQ(d.load(log), 1);
		EXPECT_TRUE(log.contains("node array")) << log.all();
	}
}

TEST(SoftBodyFile, EveryByteOfTheSoftBodyChunksFlippedNeverCrashes)
{
	// Runs under ASan in CI: whatever a byte becomes, the load reads nothing out of bounds and every body it
	// makes has finite nodes.
	SoftTestWorld a;
	btSoftBody* rope = a.addSoft(btSoftBodyHelpers::CreateRope(a.info(), btVector3(0, 2, 0), btVector3(1, 2, 0), 3, 1));
	rope->generateClusters(2);
	const std::vector<char> file = writeWorld(a.world());
	const std::vector<ChunkAt> chunks = walkChunks(file);
	const ChunkAt* body = findChunk(chunks, BT_SOFTBODY_CODE);
	ASSERT_NE(body, nullptr);
	int loaded = 0, tried = 0;
	for (size_t i = body->data; i < body->data + size_t(body->length); i += 3)
	{
		std::vector<char> copy = file;
		copy[i] = char(copy[i] ^ 0xA5);
		WarningLog log;
		SoftTestWorld w;
		btSoftBulletWorldImporter importer(&w.world());
		importer.loadFileFromMemory(copy.data(), int(copy.size()));
		loaded += importer.getNumSoftBodies();
		++tried;
		importer.deleteAllData();
	}
	EXPECT_GT(tried, 100);
	EXPECT_GT(loaded, 0);  // flips of values (not counts) still load
}

// eRESTORE_EXISTING_OBJECTS writes the rigid part into the world's objects; soft bodies are not written into
// existing ones (a soft world snapshot does that): they are reported and nothing is added.
TEST(SoftBodyFile, RestoringExistingObjectsReportsTheSoftBodiesAndAddsNothing)
{
	Scene scene;
	const std::vector<char> file = writeWorld(scene.w.world());
	const int objects = scene.w.world().getNumCollisionObjects();
	const btVector3 boxAt = scene.box->getWorldTransform().getOrigin();
	scene.w.step(10);
	ASSERT_NE(scene.box->getWorldTransform().getOrigin(), boxAt);  // it fell: the last check can fail
	caliber_test::WarningLog log;
	btSoftBulletWorldImporter importer(&scene.w.world());
	importer.setImporterFlags(eRESTORE_EXISTING_OBJECTS);
	EXPECT_FALSE(importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	EXPECT_TRUE(log.contains("the file's 2 soft bodies are not written into the world's")) << log.all();
	EXPECT_EQ(importer.getNumSoftBodies(), 0);
	EXPECT_EQ(scene.w.world().getNumCollisionObjects(), objects);
	EXPECT_EQ(scene.w.world().getSoftBodyArray().size(), 2);
	// The rigid box the cloth hangs from is back where it was saved.
	EXPECT_EQ(scene.box->getWorldTransform().getOrigin(), boxAt);
}

// A joint side names a cluster by its address, and only a body's first cluster has a chunk with its address
// (the cluster array's): joints between first clusters of two soft bodies come back joining the same two
// clusters; a joint on any other cluster is reported and skipped, never moved to the first cluster.
TEST(SoftBodyFile, JointsBetweenFirstClustersOfTwoSoftBodiesComeBackAndOtherClustersAreReported)
{
	SoftTestWorld w;
	btRigidBody* box = w.addRigid(1, btVector3(0, 3, 0), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
	btSoftBody* blocks[2];
	for (int k = 0; k < 2; ++k)
	{
		blocks[k] = w.addSoft(
		    btSoftBodyHelpers::CreateFromTetGenData(w.info(), Scene::kEle, 0, Scene::kNode, false, true, true));
		blocks[k]->translate(btVector3(btScalar(3 * k), 1, 0));
		blocks[k]->setVolumeMass(1);
		blocks[k]->generateClusters(2);
		ASSERT_EQ(blocks[k]->m_clusters.size(), 2);
	}
	btSoftBody::LJoint::Specs ls;
	ls.position = btVector3(1.5, 1.5, 0.5);
	ls.erp = btScalar(0.45);
	ls.cfm = btScalar(0.2);
	blocks[0]->appendLinearJoint(ls, blocks[0]->m_clusters[0], btSoftBody::Body(blocks[1]->m_clusters[0]));
	blocks[0]->appendLinearJoint(ls, blocks[0]->m_clusters[1], btSoftBody::Body(box));
	blocks[0]->appendLinearJoint(ls, blocks[0]->m_clusters[0], btSoftBody::Body(blocks[1]->m_clusters[1]));
	w.step(3);
	const std::vector<char> file = writeWorld(w.world());

	SoftTestWorld other;
	btSoftBulletWorldImporter importer(&other.world());
	caliber_test::WarningLog log;
	std::vector<char> copy = file;
	ASSERT_TRUE(importer.loadFileFromMemory(copy.data(), int(copy.size())));
	ASSERT_EQ(importer.getNumSoftBodies(), 2);
	btSoftBody* first = importer.getSoftBodyByIndex(0);
	btSoftBody* second = importer.getSoftBodyByIndex(1);
	ASSERT_EQ(first->m_joints.size(), 1) << log.all();
	const btSoftBody::Joint& joint = *first->m_joints[0];
	const btSoftBody::Joint& original = *blocks[0]->m_joints[0];
	EXPECT_EQ(joint.Type(), btSoftBody::Joint::eType::Linear);
	EXPECT_EQ(joint.m_bodies[0].m_soft, first->m_clusters[0]);
	EXPECT_EQ(joint.m_bodies[1].m_soft, second->m_clusters[0]);
	EXPECT_EQ(f(original.m_erp), joint.m_erp);
	EXPECT_EQ(f(original.m_cfm), joint.m_cfm);
	EXPECT_TRUE(log.contains("soft body 0: joint 1 is on a cluster other than its body's first")) << log.all();
	EXPECT_TRUE(log.contains("soft body 0: joint 2's other side is not an object of the file (or a cluster other"))
	    << log.all();
	importer.deleteAllData();
}
