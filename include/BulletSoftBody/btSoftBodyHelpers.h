// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_BODY_HELPERS_H
#define BT_SOFT_BODY_HELPERS_H

/// btSoftBodyHelpers: makers of ropes, cloth patches, ellipsoids and bodies from meshes, and debug
/// drawing of soft bodies.

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btIDebugDraw.h"

/// What btSoftBodyHelpers::Draw draws.
struct fDrawFlags
{
	enum _
	{
		Nodes = 0x0001,        ///< Nodes as small crosses.
		Links = 0x0002,        ///< Links.
		Faces = 0x0004,        ///< Faces.
		Tetras = 0x0008,       ///< Tetras.
		Normals = 0x0010,      ///< Node normals.
		Contacts = 0x0020,     ///< Rigid contacts.
		Anchors = 0x0040,      ///< Anchors.
		Notes = 0x0080,        ///< Notes.
		Clusters = 0x0100,     ///< Clusters: spokes from each centre to its nodes.
		NodeTree = 0x0200,     ///< Node tree (none kept).
		FaceTree = 0x0400,     ///< Face tree (none kept).
		ClusterTree = 0x0800,  ///< Cluster tree (none kept).
		Joints = 0x1000,       ///< Joints: their points (or axes) and the gap between the sides.
		Std = Links + Faces + Tetras + Anchors + Notes + Joints,  ///< The usual set.
		StdTetra = Std - Faces + Tetras,                          ///< The usual set for volumes.
		END
	};
};

/// Static makers and drawers.
struct btSoftBodyHelpers
{
	/// Draws psb's features chosen by drawflags.
	static void Draw(btSoftBody* psb, btIDebugDraw* idraw, int drawflags = fDrawFlags::Std);
	/// Writes the nodes' masses and areas as text (stress: nothing yet).
	static void DrawInfos(btSoftBody* psb, btIDebugDraw* idraw, bool masses, bool areas, bool stress);
	/// Draws the node tree (Caliber keeps none: the body's bounds).
	static void DrawNodeTree(btSoftBody* psb, btIDebugDraw* idraw, int mindepth = 0, int maxdepth = -1);
	/// Draws the face tree (Caliber keeps none: the body's bounds).
	static void DrawFaceTree(btSoftBody* psb, btIDebugDraw* idraw, int mindepth = 0, int maxdepth = -1);
	/// Draws the cluster tree (Caliber keeps none: the clusters' boxes, at depth 0).
	static void DrawClusterTree(btSoftBody* psb, btIDebugDraw* idraw, int mindepth = 0, int maxdepth = -1);
	/// Draws the pose matching frame.
	static void DrawFrame(btSoftBody* psb, btIDebugDraw* idraw);
	/// A rope of res + 2 nodes from from to to; fixeds: 1 fixes the first node, 2 the last.
	static btSoftBody* CreateRope(btSoftBodyWorldInfo& worldInfo, const btVector3& from, const btVector3& to, int res,
	                              int fixeds);
	/// A resx x resy grid of nodes between four corners, with links along the grid (and diagonals with
	/// gendiags) and two faces per cell; fixeds: 1, 2, 4, 8 fix corner00, 10, 01, 11.
	static btSoftBody* CreatePatch(btSoftBodyWorldInfo& worldInfo, const btVector3& corner00, const btVector3& corner10,
	                               const btVector3& corner01, const btVector3& corner11, int resx, int resy, int fixeds,
	                               bool gendiags, btScalar perturbation = 0.);
	/// CreatePatch, and writes texture coordinates to tex_coords when given (12 floats per grid cell:
	/// u, v of each corner of its two faces).
	static btSoftBody* CreatePatchUV(btSoftBodyWorldInfo& worldInfo, const btVector3& corner00,
	                                 const btVector3& corner10, const btVector3& corner01, const btVector3& corner11,
	                                 int resx, int resy, int fixeds, bool gendiags, float* tex_coords = 0);
	/// Texture coordinate id (0: u, 1: v) of grid point (ix, iy).
	static float CalculateUV(int resx, int resy, int ix, int iy, int id);
	/// A closed ellipsoid of about res nodes (the convex hull of points spread over it).
	static btSoftBody* CreateEllipsoid(btSoftBodyWorldInfo& worldInfo, const btVector3& center, const btVector3& radius,
	                                   int res);
	/// A body from a triangle mesh: vertices (x, y, z each), triangles (3 vertex indices each); one link
	/// per edge.
	static btSoftBody* CreateFromTriMesh(btSoftBodyWorldInfo& worldInfo, const btScalar* vertices, const int* triangles,
	                                     int ntriangles, bool randomizeConstraints = true);
	/// A closed body from the convex hull of the points.
	static btSoftBody* CreateFromConvexHull(btSoftBodyWorldInfo& worldInfo, const btVector3* vertices, int nvertices,
	                                        bool randomizeConstraints = true);
	/// A volume from TetGen's text formats (the contents of the .ele, .face and .node files, not their
	/// names; face may be null): nodes, tetras, links along the tetras' edges (btetralinks) and the
	/// given faces' edges (bfacelinks), faces from the .face data, and the four faces of every tetra with
	/// bfacesfromtetras.
	static btSoftBody* CreateFromTetGenData(btSoftBodyWorldInfo& worldInfo, const char* ele, const char* face,
	                                        const char* node, bool bfacelinks, bool btetralinks, bool bfacesfromtetras);
	/// Reorders links for locality (Caliber: links stay in their order).
	static void ReoptimizeLinkOrder(btSoftBody* psb);
};

#endif  // BT_SOFT_BODY_HELPERS_H
