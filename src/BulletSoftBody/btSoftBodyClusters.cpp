// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Clusters of a soft body: generateClusters (k-means), their frames, masses and inertias, the public
// impulse API, and the rigid-body moves the solver uses (btSoftBodyClusters.h). docs/soft-bodies.md,
// "Clusters".

#include "btSoftBodyClusters.h"

#include <mutex>
#include <unordered_map>

#include "LinearMath/btPolarDecomposition.h"
#include "LinearMath/btSideTable.h"
#include "btSoftBodyInternal.h"

using caliber::softBodyWarning;

namespace
{
// Which soft body owns each live cluster: joints to other bodies' clusters check it, so that a joint
// whose cluster went away (released, or its body deleted) is dropped instead of followed.
struct ClusterOwners
{
	std::mutex mutex;
	std::unordered_map<const btSoftBody::Cluster*, btSoftBody*> owners;
};
ClusterOwners& clusterOwners()
{
	static ClusterOwners* owners = new ClusterOwners();  // never destroyed (bodies may die at exit)
	return *owners;
}
void registerCluster(const btSoftBody::Cluster* c, btSoftBody* owner)
{
	ClusterOwners& o = clusterOwners();
	std::lock_guard<std::mutex> lock(o.mutex);
	o.owners[c] = owner;
}
void unregisterCluster(const btSoftBody::Cluster* c)
{
	ClusterOwners& o = clusterOwners();
	std::lock_guard<std::mutex> lock(o.mutex);
	o.owners.erase(c);
}

// Weight of node j of a cluster for its centre and frame: its mass, or 1 for every node of an
// immovable cluster (one with a fixed node), whose frame still follows its nodes.
inline btScalar frameWeight(const btSoftBody::Cluster& c, int j) { return c.m_imass > 0 ? c.m_masses[j] : btScalar(1); }

btSoftBody::Cluster* newCluster()
{
	return new (btAlignedAlloc(sizeof(btSoftBody::Cluster), 16)) btSoftBody::Cluster();
}
void deleteCluster(btSoftBody::Cluster* c)
{
	unregisterCluster(c);
	c->~Cluster();
	btAlignedFree(c);
}
}  // namespace

btSoftBody* caliber::clusterOwner(const btSoftBody::Cluster* cluster)
{
	ClusterOwners& o = clusterOwners();
	std::lock_guard<std::mutex> lock(o.mutex);
	auto it = o.owners.find(cluster);
	return it == o.owners.end() ? 0 : it->second;
}

caliber::ClusterState& caliber::clusterState(const btSoftBody& body)
{
	return sideTable<ClusterState>().acquire(&body);
}

void caliber::releaseClusterState(const btSoftBody& body) { sideTable<ClusterState>().release(&body); }

void caliber::refreshCluster(btSoftBody::Cluster& c, btScalar dt)
{
	const int n = c.m_nodes.size();
	if (n == 0) return;
	btScalar total = 0;
	btVector3 com(0, 0, 0);
	for (int j = 0; j < n; ++j)
	{
		const btScalar w = frameWeight(c, j);
		com += c.m_nodes[j]->m_x * w;
		total += w;
	}
	com /= total;
	// Inertia about the centre, and the moment of the current shape against the rest shape.
	btMatrix3x3 inertia(0, 0, 0, 0, 0, 0, 0, 0, 0), apq(0, 0, 0, 0, 0, 0, 0, 0, 0);
	btVector3 momentum(0, 0, 0), angular(0, 0, 0);
	for (int j = 0; j < n; ++j)
	{
		const btSoftBody::Node& node = *c.m_nodes[j];
		const btScalar w = frameWeight(c, j);
		const btVector3 r = node.m_x - com;
		const btScalar r2 = r.length2();
		const btVector3& ref = c.m_framerefs[j];
		for (int a = 0; a < 3; ++a)
			for (int b = 0; b < 3; ++b)
			{
				inertia[a][b] += w * ((a == b ? r2 : btScalar(0)) - r[a] * r[b]);
				apq[a][b] += w * r[a] * ref[b];
			}
		const btVector3 v = dt > 0 ? (node.m_x - node.m_q) / dt : node.m_v;
		momentum += v * w;
		angular += r.cross(v) * w;
	}
	// The previous rotation, lightly weighted, settles the directions a flat or linear cluster leaves
	// open (its moment matrix is singular there).
	const btScalar trace = inertia[0][0] + inertia[1][1] + inertia[2][2];
	const btScalar tiny = btScalar(1e-4) * (trace > 0 ? trace : btScalar(1));
	const btMatrix3x3 previous = c.m_framexform.getBasis();
	for (int a = 0; a < 3; ++a)
		for (int b = 0; b < 3; ++b) apq[a][b] += tiny * previous[a][b];
	btMatrix3x3 rot, scl;
	polarDecompose(apq, rot, scl);
	if (rot.determinant() < 0) rot = rot * btMatrix3x3(-1, 0, 0, 0, 1, 0, 0, 0, 1);
	bool finite = true;
	for (int a = 0; a < 3; ++a) finite = finite && caliber::isFinite(rot[a]);
	if (!finite) rot = previous;
	c.m_framexform.setBasis(rot);
	c.m_framexform.setOrigin(com);
	c.m_com = com;
	if (c.m_imass > 0)
	{
		// A rope-like cluster has no inertia about its line: no node moves by a turn about it anyway.
		for (int a = 0; a < 3; ++a) inertia[a][a] += tiny;
		c.m_invwi = inertia.inverse();
	}
	else
		c.m_invwi.setValue(0, 0, 0, 0, 0, 0, 0, 0, 0);
	c.m_lv = momentum / total;
	c.m_av = c.m_imass > 0 ? c.m_invwi * angular : btVector3(0, 0, 0);  // angular momentum about the centre
}

btScalar caliber::clusterInverseMass(const btSoftBody::Cluster& c, const btVector3& r, const btVector3& n)
{
	if (!(c.m_imass > 0)) return 0;
	const btVector3 rn = r.cross(n);
	// A push moves the centre by m_idmass per unit (shared nodes move by their share only).
	return c.m_idmass + (c.m_idmass / c.m_imass) * rn.dot(c.m_invwi * rn);
}

void caliber::clusterMotion(const btSoftBody::Cluster& c, btScalar dt, btVector3& com, btVector3& velocity)
{
	com.setValue(0, 0, 0);
	velocity.setValue(0, 0, 0);
	btScalar total = 0;
	for (int j = 0; j < c.m_nodes.size(); ++j)
	{
		const btSoftBody::Node& node = *c.m_nodes[j];
		const btScalar w = frameWeight(c, j);
		com += node.m_x * w;
		velocity += (node.m_x - node.m_q) * w;
		total += w;
	}
	if (!(total > 0)) return;
	com /= total;
	velocity /= total * dt;
}

int caliber::materialPointWeights(const btSoftBody::Cluster& c, const btVector3& p,
                                  btAlignedObjectArray<btScalar>& weights)
{
	const int offset = weights.size();
	const int n = c.m_nodes.size();
	weights.resize(offset + n);
	btScalar total = 0;
	btVector3 com(0, 0, 0);
	for (int j = 0; j < n; ++j)
	{
		total += frameWeight(c, j);
		com += c.m_nodes[j]->m_x * frameWeight(c, j);
	}
	if (!(total > 0)) return offset;
	com /= total;
	// Second moment A of the nodes about the centre; the weights w_j / W + w_j r_j . (A^-1 (p - com)) sum to
	// one and give back p: sum w_j r_j r_j^T A^-1 (p - com) = p - com.
	btMatrix3x3 moment(0, 0, 0, 0, 0, 0, 0, 0, 0);
	for (int j = 0; j < n; ++j)
	{
		const btVector3 r = c.m_nodes[j]->m_x - com;
		for (int a = 0; a < 3; ++a)
			for (int b = 0; b < 3; ++b) moment[a][b] += frameWeight(c, j) * r[a] * r[b];
	}
	const btScalar trace = moment[0][0] + moment[1][1] + moment[2][2];
	// A flat or linear cluster has no moment across itself: a small regularisation drops that part of p.
	for (int a = 0; a < 3; ++a) moment[a][a] += btScalar(1e-4) * (trace > 0 ? trace : btScalar(1));
	const btVector3 g = moment.inverse() * (p - com);
	for (int j = 0; j < n; ++j)
		weights[offset + j] = frameWeight(c, j) * (1 / total + (c.m_nodes[j]->m_x - com).dot(g));
	return offset;
}

btVector3 caliber::materialPoint(const btSoftBody::Cluster& c, const btAlignedObjectArray<btScalar>& weights,
                                 int offset)
{
	btVector3 p(0, 0, 0);
	for (int j = 0; j < c.m_nodes.size(); ++j) p += c.m_nodes[j]->m_x * weights[offset + j];
	return p;
}

btScalar caliber::clusterAngularInverseMass(const btSoftBody::Cluster& c, const btVector3& n)
{
	if (!(c.m_imass > 0)) return 0;
	return (c.m_idmass / c.m_imass) * n.dot(c.m_invwi * n);
}

namespace
{
// Moves every free node of c by its share of the rigid displacement dx + dw x (x - com) (a node shared
// by n clusters carries 1/n of its mass in each, and moves by 1/n of each cluster's displacement, so the
// nodes' momentum changes by exactly the push); the frame and tracked velocities follow the centre.
void displaceCluster(btSoftBody::Cluster& c, const btVector3& dx, const btVector3& dw, btScalar dt, btScalar share)
{
	btVector3 moved(0, 0, 0);
	for (int j = 0; j < c.m_nodes.size(); ++j)
	{
		btSoftBody::Node& node = *c.m_nodes[j];
		if (node.m_im <= 0) continue;
		const btVector3 d = (dx + dw.cross(node.m_x - c.m_com)) * (c.m_masses[j] * node.m_im);
		node.m_x += d;
		node.m_q += d * (1 - share);
		moved += d * c.m_masses[j];
	}
	const btVector3 dcom = moved * c.m_imass;
	const btVector3 turn = dw * (c.m_idmass / c.m_imass);
	c.m_com += dcom;
	const btScalar angle = turn.length();
	if (angle > SIMD_EPSILON)
		c.m_framexform.setBasis(btMatrix3x3(btQuaternion(turn / angle, angle)) * c.m_framexform.getBasis());
	c.m_framexform.setOrigin(c.m_com);
	if (dt > 0)
	{
		c.m_lv += dcom * (share / dt);
		c.m_av += turn * (share / dt);
	}
}
}  // namespace

void caliber::moveCluster(btSoftBody::Cluster& c, const btVector3& p, const btVector3& r, btScalar dt,
                          btScalar velocityShare)
{
	if (!(c.m_imass > 0)) return;
	displaceCluster(c, p * c.m_imass, c.m_invwi * r.cross(p), dt, velocityShare);
}

void caliber::turnCluster(btSoftBody::Cluster& c, const btVector3& l, btScalar dt, btScalar velocityShare)
{
	if (!(c.m_imass > 0)) return;
	displaceCluster(c, btVector3(0, 0, 0), c.m_invwi * l, dt, velocityShare);
}

int btSoftBody::generateClusters(int k, int maxiterations)
{
	releaseClusters();
	const int n = m_nodes.size();
	if (n == 0)
	{
		softBodyWarning("Caliber: btSoftBody::generateClusters: the body has no nodes; no clusters\n");
		return 0;
	}
	if (k > n)
	{
		softBodyWarning(
		    "Caliber: btSoftBody::generateClusters: more clusters asked for than there are nodes; one per node\n");
		k = n;
	}
	if (k > 0)
	{
		if (maxiterations < 1)
		{
			softBodyWarning("Caliber: btSoftBody::generateClusters: maxiterations < 1; one round of k-means\n");
			maxiterations = 1;
		}
		// k-means (Lloyd) over the node positions, seeded by nodes spread evenly through the node list
		// (deterministic); stops when no node changes cluster.
		btAlignedObjectArray<btVector3> centres;
		btAlignedObjectArray<int> owner, count;
		centres.resize(k);
		count.resize(k);
		owner.resize(n, -1);
		for (int i = 0; i < k; ++i) centres[i] = m_nodes[int((long long)i * n / k)].m_x;
		for (int it = 0; it < maxiterations; ++it)
		{
			bool changed = false;
			for (int j = 0; j < n; ++j)
			{
				int best = 0;
				btScalar bestD2 = (m_nodes[j].m_x - centres[0]).length2();
				for (int i = 1; i < k; ++i)
				{
					const btScalar d2 = (m_nodes[j].m_x - centres[i]).length2();
					if (d2 < bestD2)
					{
						bestD2 = d2;
						best = i;
					}
				}
				if (owner[j] != best)
				{
					owner[j] = best;
					changed = true;
				}
			}
			if (!changed) break;
			for (int i = 0; i < k; ++i)
			{
				count[i] = 0;
				centres[i].setValue(0, 0, 0);
			}
			for (int j = 0; j < n; ++j)
			{
				centres[owner[j]] += m_nodes[j].m_x;
				++count[owner[j]];
			}
			for (int i = 0; i < k; ++i)
				if (count[i] > 0) centres[i] /= btScalar(count[i]);
		}
		btAlignedObjectArray<Cluster*> made;
		made.resize(k);
		for (int i = 0; i < k; ++i) made[i] = newCluster();
		for (int j = 0; j < n; ++j) made[owner[j]]->m_nodes.push_back(&m_nodes[j]);
		// Neighbours share their border: a cluster takes in the other nodes of each face (or, without
		// faces, link) that has a node of its own, so that the clusters hang together.
		auto takeIn = [&](Node* a, Node* b)
		{
			Cluster* c = made[owner[int(a - &m_nodes[0])]];
			if (owner[int(a - &m_nodes[0])] != owner[int(b - &m_nodes[0])] &&
			    c->m_nodes.findLinearSearch(b) == c->m_nodes.size())
				c->m_nodes.push_back(b);
		};
		if (m_faces.size() > 0)
		{
			for (int f = 0; f < m_faces.size(); ++f)
				for (int a = 0; a < 3; ++a)
					for (int b = 0; b < 3; ++b)
						if (a != b) takeIn(m_faces[f].m_n[a], m_faces[f].m_n[b]);
		}
		else
			for (int l = 0; l < m_links.size(); ++l)
			{
				takeIn(m_links[l].m_n[0], m_links[l].m_n[1]);
				takeIn(m_links[l].m_n[1], m_links[l].m_n[0]);
			}
		for (int i = 0; i < k; ++i)
			if (made[i]->m_nodes.size() > 0)
				m_clusters.push_back(made[i]);
			else
				deleteCluster(made[i]);
	}
	else
	{
		// One cluster per tetra, else per face, else per link.
		auto add = [&](Node* const* nodes, int count)
		{
			Cluster* c = newCluster();
			for (int j = 0; j < count; ++j) c->m_nodes.push_back(nodes[j]);
			m_clusters.push_back(c);
		};
		if (m_tetras.size() > 0)
			for (int i = 0; i < m_tetras.size(); ++i) add(m_tetras[i].m_n, 4);
		else if (m_faces.size() > 0)
			for (int i = 0; i < m_faces.size(); ++i) add(m_faces[i].m_n, 3);
		else if (m_links.size() > 0)
			for (int i = 0; i < m_links.size(); ++i) add(m_links[i].m_n, 2);
		else
		{
			softBodyWarning(
			    "Caliber: btSoftBody::generateClusters: k <= 0 asks for a cluster per tetra, face or link, and the "
			    "body has none; no clusters\n");
			return 0;
		}
	}
	for (int i = 0; i < m_clusters.size(); ++i)
	{
		m_clusters[i]->m_clusterIndex = i;
		m_clusters[i]->m_collide = true;
		registerCluster(m_clusters[i], this);
	}
	initializeClusters();
	// Clusters that share a node are neighbours: self-collision leaves them alone.
	const int count = m_clusters.size();
	m_clusterConnectivity.resize(count * count);
	for (int i = 0; i < count * count; ++i) m_clusterConnectivity[i] = false;
	btAlignedObjectArray<int> seen;
	seen.resize(n, -1);
	btAlignedObjectArray<btAlignedObjectArray<int>> memberOf;
	memberOf.resize(n);
	for (int i = 0; i < count; ++i)
		for (int j = 0; j < m_clusters[i]->m_nodes.size(); ++j)
			memberOf[int(m_clusters[i]->m_nodes[j] - &m_nodes[0])].push_back(i);
	for (int j = 0; j < n; ++j)
		for (int a = 0; a < memberOf[j].size(); ++a)
			for (int b = 0; b < memberOf[j].size(); ++b)
				m_clusterConnectivity[memberOf[j][a] + memberOf[j][b] * count] = true;
	return count;
}

void btSoftBody::initializeClusters()
{
	btAlignedObjectArray<int> memberships;
	memberships.resize(m_nodes.size(), 0);
	for (int i = 0; i < m_clusters.size(); ++i)
		for (int j = 0; j < m_clusters[i]->m_nodes.size(); ++j)
			++memberships[int(m_clusters[i]->m_nodes[j] - &m_nodes[0])];
	for (int i = 0; i < m_clusters.size(); ++i)
	{
		Cluster& c = *m_clusters[i];
		const int n = c.m_nodes.size();
		c.m_masses.resize(n);
		btScalar total = 0;
		bool fixed = false;
		c.m_containsAnchor = false;
		for (int j = 0; j < n; ++j)
		{
			const Node& node = *c.m_nodes[j];
			// A node shared by several clusters gives each an equal part of its mass: the clusters' masses
			// add up to the body's.
			const int shared = memberships[int(c.m_nodes[j] - &m_nodes[0])];
			c.m_masses[j] = node.m_im > 0 ? btScalar(1) / (node.m_im * btScalar(shared)) : btScalar(0);
			fixed = fixed || node.m_im <= 0;
			total += c.m_masses[j];
			if (node.m_battach) c.m_containsAnchor = true;
		}
		// A cluster with a fixed node does not move as a whole (its free nodes still move with the links).
		c.m_imass = (fixed || !(total > 0)) ? btScalar(0) : btScalar(1) / total;
		// A push P moves node j by its share s_j = m_masses[j] / (node mass) of the rigid displacement
		// P / mass, so the centre moves by P sum(m_masses[j] s_j) / mass^2: that is the inverse mass a
		// contact sees (m_imass when no node is shared).
		btScalar seen = 0;
		for (int j = 0; j < n; ++j) seen += c.m_masses[j] * c.m_masses[j] * c.m_nodes[j]->m_im;
		c.m_idmass = c.m_imass * c.m_imass * seen;
		btVector3 com(0, 0, 0);
		btScalar weights = 0;
		for (int j = 0; j < n; ++j)
		{
			com += c.m_nodes[j]->m_x * frameWeight(c, j);
			weights += frameWeight(c, j);
		}
		com /= weights;
		c.m_framerefs.resize(n);
		btMatrix3x3 inertia(0, 0, 0, 0, 0, 0, 0, 0, 0);
		for (int j = 0; j < n; ++j)
		{
			const btVector3 r = c.m_nodes[j]->m_x - com;
			c.m_framerefs[j] = r;
			const btScalar w = frameWeight(c, j);
			for (int a = 0; a < 3; ++a)
				for (int b = 0; b < 3; ++b) inertia[a][b] += w * ((a == b ? r.length2() : btScalar(0)) - r[a] * r[b]);
		}
		const btScalar trace = inertia[0][0] + inertia[1][1] + inertia[2][2];
		for (int a = 0; a < 3; ++a) inertia[a][a] += btScalar(1e-4) * (trace > 0 ? trace : btScalar(1));
		c.m_locii = inertia.inverse();
		c.m_framexform.setIdentity();
		c.m_framexform.setOrigin(com);
		c.m_com = com;
		c.m_invwi = c.m_imass > 0 ? c.m_locii : btMatrix3x3(0, 0, 0, 0, 0, 0, 0, 0, 0);
		c.m_lv.setValue(0, 0, 0);
		c.m_av.setValue(0, 0, 0);
	}
	cleanupClusters();
}

void btSoftBody::updateClusters()
{
	for (int i = 0; i < m_clusters.size(); ++i)
	{
		Cluster& c = *m_clusters[i];
		caliber::refreshCluster(c, 0);
		if (c.m_matching > 0)
		{
			const btScalar k = btClamped(c.m_matching, btScalar(0), btScalar(1));
			for (int j = 0; j < c.m_nodes.size(); ++j)
			{
				Node& node = *c.m_nodes[j];
				if (node.m_im > 0) node.m_x += (c.m_framexform * c.m_framerefs[j] - node.m_x) * k;
			}
		}
	}
}

void btSoftBody::cleanupClusters()
{
	for (int i = 0; i < m_clusters.size(); ++i)
	{
		Cluster& c = *m_clusters[i];
		c.m_vimpulses[0] = c.m_vimpulses[1] = c.m_dimpulses[0] = c.m_dimpulses[1] = btVector3(0, 0, 0);
		c.m_nvimpulses = c.m_ndimpulses = 0;
	}
}

void btSoftBody::applyClusters(bool drift)
{
	const btScalar dt = m_sst.sdt;
	for (int i = 0; i < m_clusters.size(); ++i)
	{
		Cluster& c = *m_clusters[i];
		if ((drift ? c.m_ndimpulses : c.m_nvimpulses) == 0) continue;
		const btVector3& lin = drift ? c.m_dimpulses[0] : c.m_vimpulses[0];
		const btVector3& ang = drift ? c.m_dimpulses[1] : c.m_vimpulses[1];
		// Each cluster moves its own nodes as a rigid body, each node by its share (summed over the
		// clusters it is in), so the nodes' momentum changes by exactly the impulses given.
		for (int j = 0; j < c.m_nodes.size(); ++j)
		{
			Node& node = *c.m_nodes[j];
			if (node.m_im <= 0) continue;
			// The node's share of the cluster's rigid motion (1/n for a node in n clusters).
			const btVector3 dv = (lin + ang.cross(node.m_x - c.m_com)) * (c.m_masses[j] * node.m_im);
			if (drift)
				node.m_x += dv * dt;
			else
				node.m_v += dv;
		}
	}
	if (drift)
		for (int i = 0; i < m_clusters.size(); ++i)
		{
			m_clusters[i]->m_dimpulses[0] = m_clusters[i]->m_dimpulses[1] = btVector3(0, 0, 0);
			m_clusters[i]->m_ndimpulses = 0;
		}
	else
		for (int i = 0; i < m_clusters.size(); ++i)
		{
			m_clusters[i]->m_vimpulses[0] = m_clusters[i]->m_vimpulses[1] = btVector3(0, 0, 0);
			m_clusters[i]->m_nvimpulses = 0;
		}
}

void btSoftBody::dampClusters()
{
	for (int i = 0; i < m_clusters.size(); ++i)
	{
		Cluster& c = *m_clusters[i];
		if (!(c.m_ndamping > 0) && !(c.m_ldamping > 0) && !(c.m_adamping > 0)) continue;
		caliber::refreshCluster(c, 0);
		const btScalar nd = btClamped(c.m_ndamping, btScalar(0), btScalar(1));
		const btScalar ld = btClamped(c.m_ldamping, btScalar(0), btScalar(1));
		const btScalar ad = btClamped(c.m_adamping, btScalar(0), btScalar(1));
		for (int j = 0; j < c.m_nodes.size(); ++j)
		{
			Node& node = *c.m_nodes[j];
			if (node.m_im <= 0) continue;
			const btVector3 r = node.m_x - c.m_com;
			// The node's motion relative to the cluster's rigid motion loses nd of itself; the rigid motion
			// loses ld (linear) and ad (angular).
			const btVector3 rigid = c.m_lv + c.m_av.cross(r);
			node.m_v += (rigid - node.m_v) * nd;
			node.m_v -= c.m_lv * ld + (c.m_av * ad).cross(r);
		}
	}
}

void btSoftBody::releaseCluster(int index)
{
	if (!caliber::validIndex(index, m_clusters.size()))
	{
		btAssert(!"btSoftBody::releaseCluster: cluster index out of range");
		softBodyWarning("Caliber: btSoftBody::releaseCluster: cluster index out of range; ignored\n");
		return;
	}
	Cluster* c = m_clusters[index];
	for (int i = m_joints.size() - 1; i >= 0; --i)
	{
		Joint* j = m_joints[i];
		if (j->m_bodies[0].m_soft == c || j->m_bodies[1].m_soft == c)
		{
			j->~Joint();
			btAlignedFree(j);
			m_joints.removeAtIndex(i);
		}
	}
	caliber::removeClusterLeaf(*this, *c);
	deleteCluster(c);
	m_clusters.removeAtIndex(index);
	for (int i = 0; i < m_clusters.size(); ++i) m_clusters[i]->m_clusterIndex = i;
	// Connectivity without the released row and column.
	const int count = m_clusters.size();
	if (m_clusterConnectivity.size() == (count + 1) * (count + 1))
	{
		btAlignedObjectArray<bool> kept;
		kept.resize(count * count);
		for (int a = 0, ra = 0; a <= count; ++a)
		{
			if (a == index) continue;
			for (int b = 0, rb = 0; b <= count; ++b)
			{
				if (b == index) continue;
				kept[ra + rb * count] = m_clusterConnectivity[a + b * (count + 1)];
				++rb;
			}
			++ra;
		}
		m_clusterConnectivity = kept;
	}
	else
		m_clusterConnectivity.resize(0);
}

void btSoftBody::releaseClusters()
{
	while (m_clusters.size() > 0) releaseCluster(m_clusters.size() - 1);
	m_clusterConnectivity.resize(0);
}

btVector3 btSoftBody::clusterCom(const Cluster* cluster)
{
	if (!cluster || cluster->m_nodes.size() == 0) return btVector3(0, 0, 0);
	btVector3 com(0, 0, 0);
	btScalar total = 0;
	for (int j = 0; j < cluster->m_nodes.size(); ++j)
	{
		const btScalar w = frameWeight(*cluster, j);
		com += cluster->m_nodes[j]->m_x * w;
		total += w;
	}
	return com / total;
}

btVector3 btSoftBody::clusterCom(int cluster) const
{
	if (!caliber::validIndex(cluster, m_clusters.size()))
	{
		btAssert(!"btSoftBody::clusterCom: cluster index out of range");
		softBodyWarning("Caliber: btSoftBody::clusterCom: cluster index out of range; the origin is returned\n");
		return btVector3(0, 0, 0);
	}
	return clusterCom(m_clusters[cluster]);
}

btVector3 btSoftBody::clusterVelocity(const Cluster* cluster, const btVector3& rpos)
{
	return cluster->m_lv + cluster->m_av.cross(rpos);
}

void btSoftBody::clusterVImpulse(Cluster* cluster, const btVector3& rpos, const btVector3& impulse)
{
	const btVector3 li = impulse * cluster->m_imass;
	const btVector3 ai = cluster->m_invwi * rpos.cross(impulse);
	cluster->m_vimpulses[0] += li;
	cluster->m_vimpulses[1] += ai;
	cluster->m_lv += li;
	cluster->m_av += ai;
	++cluster->m_nvimpulses;
}

void btSoftBody::clusterDImpulse(Cluster* cluster, const btVector3& rpos, const btVector3& impulse)
{
	cluster->m_dimpulses[0] += impulse * cluster->m_imass;
	cluster->m_dimpulses[1] += cluster->m_invwi * rpos.cross(impulse);
	++cluster->m_ndimpulses;
}

void btSoftBody::clusterImpulse(Cluster* cluster, const btVector3& rpos, const Impulse& impulse)
{
	if (impulse.m_asVelocity) clusterVImpulse(cluster, rpos, impulse.m_velocity);
	if (impulse.m_asDrift) clusterDImpulse(cluster, rpos, impulse.m_drift);
}

void btSoftBody::clusterVAImpulse(Cluster* cluster, const btVector3& impulse)
{
	const btVector3 ai = cluster->m_invwi * impulse;
	cluster->m_vimpulses[1] += ai;
	cluster->m_av += ai;
	++cluster->m_nvimpulses;
}

void btSoftBody::clusterDAImpulse(Cluster* cluster, const btVector3& impulse)
{
	cluster->m_dimpulses[1] += cluster->m_invwi * impulse;
	++cluster->m_ndimpulses;
}

void btSoftBody::clusterAImpulse(Cluster* cluster, const Impulse& impulse)
{
	if (impulse.m_asVelocity) clusterVAImpulse(cluster, impulse.m_velocity);
	if (impulse.m_asDrift) clusterDAImpulse(cluster, impulse.m_drift);
}

void btSoftBody::clusterDCImpulse(Cluster* cluster, const btVector3& impulse)
{
	cluster->m_dimpulses[0] += impulse * cluster->m_imass;
	++cluster->m_ndimpulses;
}

btSoftBody::Cluster* caliber::appendCluster(btSoftBody& body)
{
	btSoftBody::Cluster* c = newCluster();
	c->m_clusterIndex = body.m_clusters.size();
	body.m_clusters.push_back(c);
	registerCluster(c, &body);
	return c;
}
