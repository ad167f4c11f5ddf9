// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The multithreaded sequential-impulse solver: the contacts of a large solve coloured so that the
// manifolds of one colour share no dynamic body, and each colour's manifolds solved in batches on the
// task scheduler's threads.
//
// Why the bits do not depend on threads: the manifolds of a colour touch disjoint dynamic bodies, so
// solving them in any order, on any threads, gives the same numbers; colours run one after another in
// a fixed order, and the residual is summed batch by batch in batch order (btParallelSum). The one body
// many manifolds of a colour share is the solver's fixed entry for static objects: it takes impulses of
// zero, but concurrent writes would still race, so each batch gets its own copy of it (identical,
// and it stays zero).
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <atomic>
#include <thread>

#if defined(__SSE2__) || defined(__x86_64__) || defined(_M_X64)
#include <emmintrin.h>
#endif

#include "BulletCollision/CollisionDispatch/btManifoldOwners.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletDynamics/ConstraintSolver/btBatchDependencies.h"
#include "BulletDynamics/ConstraintSolver/btContactColouring.h"
#include "BulletDynamics/ConstraintSolver/btContactRowSetup.h"
#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"
#include "BulletDynamics/ConstraintSolver/btSolverRowSolvers.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/ConstraintSolver/btWideContactRows.h"
#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/btScratchArray.h"
#include "LinearMath/btSideTable.h"

bool btSequentialImpulseConstraintSolverMt::s_allowNestedParallelForLoops = false;
int btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = 250;
int btSequentialImpulseConstraintSolverMt::s_minBatchSize = 50;
int btSequentialImpulseConstraintSolverMt::s_maxBatchSize = 100;
btBatchedConstraints::BatchingMethod btSequentialImpulseConstraintSolverMt::s_contactBatchingMethod =
    btBatchedConstraints::BATCHING_METHOD_SPATIAL_GRID_2D;
btBatchedConstraints::BatchingMethod btSequentialImpulseConstraintSolverMt::s_jointBatchingMethod =
    btBatchedConstraints::BATCHING_METHOD_SPATIAL_GRID_2D;

namespace
{
// The threads a solve spreads over: one when it runs inside a parallel loop's task (the island dispatch
// solves a whole group of large batches on one thread beside the small ones), whose nested loops run on
// that thread anyway. The solve's bits are the same at any count.
int solveThreads() { return caliber::insideParallelBody() ? 1 : btMax(1, btGetTaskScheduler()->getNumThreads()); }

// The Mt solver's own per-solve state (beside Bullet's class), reused from solve to solve.
struct MtSolverScratch
{
	caliber::ContactColouring colouring;    // each manifold's colour
	btAlignedObjectArray<int> colourCount;  // manifolds per colour
	btAlignedObjectArray<int> colourRows;   // contact rows per colour
	btAlignedObjectArray<int> colourCursor;
	btAlignedObjectArray<int> orderedManifolds;  // manifolds colour by colour
	btAlignedObjectArray<int> bodyOrder;         // counting sort by first moving body
	btAlignedObjectArray<int> byBody;
	btAlignedObjectArray<btScalar> batchResidual;
	btAlignedObjectArray<int> rollingStart;                  // per contact row, its first rolling row in rollingRows
	btAlignedObjectArray<int> rollingRows;                   // rolling rows grouped by contact row
	btAlignedObjectArray<caliber::ContactPointRows> points;  // the points with rows, in order
	// Per manifold of the solve: its solver bodies (-1: no rows; kLookUpSerially: see FindManifoldBodies),
	// and its planned points.
	btAlignedObjectArray<int> manifoldBodies;                 // two per manifold
	btAlignedObjectArray<int> plannedCount;                   // per manifold
	btAlignedObjectArray<int> plannedRolling;                 // per manifold: rolling rows of its points
	btAlignedObjectArray<caliber::ContactPointRows> planned;  // MANIFOLD_CACHE_SIZE per manifold
	// Per chunk of kManifoldsPerPlaceTask manifolds (and one past the last): the points, rolling rows and
	// manifolds with rows before it (counted on the threads, summed in chunk order).
	struct PlaceChunkStart
	{
		int points, rolling, rowManifolds;
	};
	btAlignedObjectArray<PlaceChunkStart> placeChunkStart;
	// Per manifold with rows, in order: what the colouring, the ordering and the warm starts read, in one
	// small array instead of each manifold's first row (a cache line apiece, a manifold apart).
	struct RowManifold
	{
		int bodyA, bodyB;  // its solver bodies, as in its rows (before the fixed entry's copies)
		int firstPoint;    // its first point in points (its rows follow the points)
		int numPoints;
	};
	btAlignedObjectArray<RowManifold> rowManifolds;
	// Per manifold with rows: its manifold, for the write-back's note of its owner (btManifoldOwners.h).
	btAlignedObjectArray<const btPersistentManifold*> rowManifoldSource;
	// Per batch: its first manifold in orderedManifolds (and one past the last batch), and the body its
	// padding lanes and static contacts use (its own copy of the fixed entry, or a zero body).
	btAlignedObjectArray<int> batchManifoldBegin;
	btAlignedObjectArray<int> batchPaddingBody;
	// The batches grouped by the thread whose run of the sweep holds them (run 0's, then run 1's, ...; in
	// batch order within a run): the loops by batch before and after the sweeps (the batches' row lists,
	// the fixed entry's copies, the wide blocks' fill and impulses, the contacts' write-back) take them in
	// this order, so that the pool's contiguous share of a loop for a thread holds the batches that thread
	// sweeps, and their rows and blocks stay in its core's cache from stage to stage (see
	// listBatchesByRun).
	btAlignedObjectArray<int> batchesByRun;
	btAlignedObjectArray<int> batchRun;  // per batch: its run (listed with batchesByRun)
	// The solver bodies of the plan grouped the same way (run 0's, then run 1's, ...; in index order within
	// a run): a body goes with the run that holds most of its manifolds (a one-pass majority vote over the
	// batches in order); a body in no batch (the fixed entry, a body with joints only) with the run of its
	// share of the index range. The warm starts and the bodies' write-back take them in this order, one slice of
	// a run per task (BodySlices), so that a thread warms and writes back the bodies its runs sweep.
	// bodyRunStart: per run and one past the last, its first entry; empty when not listed (one run).
	btAlignedObjectArray<int> bodiesByRun;
	btAlignedObjectArray<int> bodyRunStart;
	btAlignedObjectArray<int> bodyRun;    // listBodiesByRun's scratch: per solver body, its run
	btAlignedObjectArray<int> bodyVotes;  // and the run's lead in its vote
	// The warm starts by body: each moving body's manifolds (index in rowManifolds << 1 | side B), in the
	// order the serial setup applies them.
	btAlignedObjectArray<int> warmStartFirst;  // per solver body, and one past the last
	btAlignedObjectArray<int> warmStarts;
	// Per chunk of the manifolds (kWarmStartChunks) and solver body: its entries in the chunk, then where the
	// chunk's first entry of that body goes.
	btAlignedObjectArray<int> warmStartChunkCursor;
	bool wide;  // the batches are solved by the wide sweep
	caliber::WideContactRows wideRows;
	// The sweep without a wait per colour (see solveSingleIteration): each batch's dependencies, the items
	// (runs of a colour's batches in one pass) in the order the threads claim them, the claim counter, and
	// per item (pass, batch) the loop that finished it.
	bool dependentSweep = false;
	// The dependencies are listed (more than one thread at the set-up). With one thread the loop has one
	// task, which runs the items in the sweep's order: every dependency is finished before it is needed.
	bool dependenciesListed = false;
	caliber::BatchDependencies dependencies;
	// The manifolds with rows that the colours, their order, the batches' ranges and the dependencies'
	// sort by body were made for, beside the contact rows' fill (see planColourSweep); -1: not made.
	int plannedManifolds = -1;
	using SweepItem = caliber::SweepItem;
	// Per direction (forwards, backwards), listed once per solve for itemThreads threads (0: not listed).
	btAlignedObjectArray<SweepItem> sweepItems[2];
	btAlignedObjectArray<int> itemOfBatch[2];  // per (pass, batch): its item
	int itemThreads[2] = {0, 0};
	// Each flag fills a cache line of its own: the threads set and read the flags of neighbouring batches
	// and items all through a sweep, and with sixteen flags to a line a store by one thread takes the line
	// from the other's cache even when the two touch different flags (false sharing).
	struct DoneFlag
	{
		std::atomic<unsigned> loop{0};
		char padding[64 - sizeof(std::atomic<unsigned>)];
		DoneFlag() {}
		DoneFlag(const DoneFlag& other) : loop(other.loop.load(std::memory_order_relaxed)) {}
		DoneFlag& operator=(const DoneFlag& other)
		{
			loop.store(other.loop.load(std::memory_order_relaxed), std::memory_order_relaxed);
			return *this;
		}
	};
	static_assert(sizeof(DoneFlag) == 64, "a flag per cache line");
	btAlignedObjectArray<DoneFlag> itemDone;     // per (pass, batch)
	btAlignedObjectArray<DoneFlag> itemClaimed;  // per item: the loop that claimed it
	unsigned sweepLoop = 0;                      // loops posted, to tell this loop's finished items from earlier loops'
	// The split-impulse pass's rows with a push target, listed by chunk of the contact order on the threads.
	struct PushChunk
	{
		btAlignedObjectArray<int> rows;
		char padding[64];  // two chunks' array headers, written by two threads, on different cache lines
	};
	btAlignedObjectArray<PushChunk> pushChunks;
};

// A loop over the listed bodies (mt.bodiesByRun) in slicesPerRun slices of every run, run after run: the
// pool hands taker t the t-th contiguous share of a loop's chunks, here exactly run t's bodies when the
// loop has as many takers as runs (a near share otherwise, or whole slices to any thread for other
// schedulers: the same results).
struct BodySlices
{
	const int* bodies;
	const int* runStart;
	int runs;
	int slicesPerRun;

	// From the listing, slices of about bodiesPerSlice bodies; runs == 0 when nothing is listed for
	// numBodies bodies.
	static BodySlices of(const MtSolverScratch& mt, int numBodies, int bodiesPerSlice)
	{
		BodySlices slices = {0, 0, 0, 1};
		const int runs = mt.bodyRunStart.size() - 1;
		if (runs < 2 || mt.bodiesByRun.size() != numBodies || mt.bodyRunStart[runs] != numBodies) return slices;
		slices.bodies = &mt.bodiesByRun[0];
		slices.runStart = &mt.bodyRunStart[0];
		slices.runs = runs;
		const int perRun = (numBodies + runs - 1) / runs;
		slices.slicesPerRun = btMax(1, (perRun + bodiesPerSlice - 1) / bodiesPerSlice);
		return slices;
	}
	int count() const { return runs * slicesPerRun; }
	// Slice c's entries of bodies, [begin, end).
	void slice(int c, int& begin, int& end) const
	{
		const int run = c / slicesPerRun, part = c % slicesPerRun;
		const int first = runStart[run], size = runStart[run + 1] - first;
		begin = first + int((long long)size * part / slicesPerRun);
		end = first + int((long long)size * (part + 1) / slicesPerRun);
	}
};

MtSolverScratch& mtScratchOf(const btSequentialImpulseConstraintSolverMt& solver)
{
	return caliber::sideTable<MtSolverScratch>().acquire(&solver);
}

// The lower solver body of a manifold that is not the fixed entry (its sort key).
int firstMovingBody(const MtSolverScratch::RowManifold& manifold, int fixedBodyId)
{
	if (manifold.bodyA == fixedBodyId) return manifold.bodyB;
	if (manifold.bodyB == fixedBodyId) return manifold.bodyA;
	return btMin(manifold.bodyA, manifold.bodyB);
}

// The rows of a batch's manifolds, in the order a sweep takes them. The manifolds of a batch share no
// moving body, so any order gives the same numbers; the order chosen lets the processor overlap rows:
// in blocks of a few manifolds, the first point of each, then the second of each, ... (consecutive
// rows of one manifold would each wait for the previous one's body update). As in the serial solver,
// which point of a manifold comes first changes from solve to solve, so that no point takes more than
// its share of the impulse step after step.
void writeBatchRows(const int* manifolds, int numManifolds, const btAlignedObjectArray<int>& manifoldFirstRow,
                    unsigned int solveCount, int* rows)
{
	const int kInterleave = 8;
	for (int blockStart = 0; blockStart < numManifolds; blockStart += kInterleave)
	{
		const int blockEnd = btMin(blockStart + kInterleave, numManifolds);
		int maxCount = 0;
		for (int b = blockStart; b < blockEnd; ++b)
			maxCount = btMax(maxCount, manifoldFirstRow[manifolds[b] + 1] - manifoldFirstRow[manifolds[b]]);
		for (int p = 0; p < maxCount; ++p)
			for (int b = blockStart; b < blockEnd; ++b)
			{
				const int first = manifoldFirstRow[manifolds[b]];
				const int count = manifoldFirstRow[manifolds[b] + 1] - first;
				if (p >= count) continue;
				const int rotated = p + int(solveCount % unsigned(count));
				*rows++ = first + (rotated < count ? rotated : rotated - count);
			}
	}
}

// Rows and bodies per task of the parallel write-back.
const int kRowsPerWriteBackTask = 256;
const int kBodiesPerWriteBackTask = 128;

// Points per task of the parallel row setup.
const int kPointsPerTask = 64;

// Manifolds per task of the parallel planning.
const int kManifoldsPerTask = 32;

// A manifold end whose object has no solver body yet: convertContacts makes it on the calling thread.
const int kLookUpSerially = -2;

// The solver body of an object whose companion id already names its entry in the pool, else
// kLookUpSerially (the test getOrInitSolverBody makes first; reading only, so any thread).
int solverBodyFromCompanionId(const btCollisionObject& object, const btAlignedObjectArray<btSolverBody>& bodies)
{
	const int hint = object.getCompanionId();
	if (hint >= 0 && hint < bodies.size() && bodies[hint].m_originalBody == &object) return hint;
	return kLookUpSerially;
}

// Each manifold's two solver bodies where the pool already holds them (-1 for a manifold without both
// objects: it gets no rows).
struct FindManifoldBodies : public btIParallelForBody
{
	btPersistentManifold** manifolds;
	MtSolverScratch* mt;
	const btAlignedObjectArray<btSolverBody>* bodies;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			const btCollisionObject* object0 = manifolds[i]->getBody0();
			const btCollisionObject* object1 = manifolds[i]->getBody1();
			int* ids = &mt->manifoldBodies[2 * i];
			if (!object0 || !object1)
			{
				ids[0] = ids[1] = -1;
				continue;
			}
			ids[0] = solverBodyFromCompanionId(*object0, *bodies);
			ids[1] = solverBodyFromCompanionId(*object1, *bodies);
		}
	}
};

// Which points of each manifold get rows (each manifold's own points: any order, any thread).
struct PlanManifolds : public btIParallelForBody
{
	btPersistentManifold** manifolds;
	MtSolverScratch* mt;
	const btAlignedObjectArray<btSolverBody>* bodies;
	const btContactSolverInfo* info;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			int& count = mt->plannedCount[i];
			int& rolling = mt->plannedRolling[i];
			count = rolling = 0;
			const int idA = mt->manifoldBodies[2 * i], idB = mt->manifoldBodies[2 * i + 1];
			if (idA < 0 || !caliber::solverBodiesCanMove(*bodies, idA, idB)) continue;
			btPersistentManifold* manifold = manifolds[i];
			btCollisionObject* colObj0 = const_cast<btCollisionObject*>(manifold->getBody0());
			btCollisionObject* colObj1 = const_cast<btCollisionObject*>(manifold->getBody1());
			const int numContacts = btMin(manifold->getNumContacts(), int(MANIFOLD_CACHE_SIZE));
			for (int j = 0; j < numContacts; ++j)
			{
				caliber::ContactPointRows& point = mt->planned[i * MANIFOLD_CACHE_SIZE + count];
				if (!caliber::planContactPoint(*manifold, j, colObj0, colObj1, idA, idB, *bodies, *info, point))
					continue;
				rolling += caliber::rollingRowsOf(*point.cp);
				++count;
			}
		}
	}
};

// Manifolds per chunk of the places' count (each index of the two loops below is one chunk).
const int kManifoldsPerPlaceTask = 256;

// Each chunk's points, rolling rows and manifolds with rows (what the serial setup counts manifold by
// manifold), into placeChunkStart[chunk + 1]; the calling thread then sums them in chunk order.
struct CountPlaces : public btIParallelForBody
{
	MtSolverScratch* mt;
	int numManifolds;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int chunk = iBegin; chunk < iEnd; ++chunk)
		{
			const int end = btMin((chunk + 1) * kManifoldsPerPlaceTask, numManifolds);
			MtSolverScratch::PlaceChunkStart sum = {0, 0, 0};
			for (int i = chunk * kManifoldsPerPlaceTask; i < end; ++i)
			{
				const int count = mt->plannedCount[i];
				if (count == 0) continue;
				sum.points += count;
				sum.rolling += mt->plannedRolling[i];
				++sum.rowManifolds;
			}
			mt->placeChunkStart[chunk + 1] = sum;
		}
	}
};

// From each chunk's starts: its manifolds' entries in the lists of manifolds with rows (manifoldFirstRow,
// rowManifolds), and its planned points in their places in the solve's point list, with their rows'
// indices. Every value is the serial setup's count at that manifold, and each chunk writes only its own
// entries, so any split of the chunks writes the same.
struct PlacePoints : public btIParallelForBody
{
	MtSolverScratch* mt;
	btPersistentManifold* const* manifolds;
	int* manifoldFirstRow;  // the solve's first entry for manifolds with rows
	int numManifolds;
	int contactBase;
	int frictionBase;
	int rollingBase;
	int frictionRowsPerContact;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int chunk = iBegin; chunk < iEnd; ++chunk)
		{
			const MtSolverScratch::PlaceChunkStart& start = mt->placeChunkStart[chunk];
			int numPoints = start.points, nextRolling = rollingBase + start.rolling, rowManifold = start.rowManifolds;
			const int end = btMin((chunk + 1) * kManifoldsPerPlaceTask, numManifolds);
			for (int i = chunk * kManifoldsPerPlaceTask; i < end; ++i)
			{
				const int count = mt->plannedCount[i];
				if (count == 0) continue;
				manifoldFirstRow[rowManifold] = contactBase + numPoints;
				mt->rowManifoldSource[rowManifold] = manifolds[i];
				MtSolverScratch::RowManifold& manifold = mt->rowManifolds[rowManifold++];
				manifold.bodyA = mt->manifoldBodies[2 * i];
				manifold.bodyB = mt->manifoldBodies[2 * i + 1];
				manifold.firstPoint = numPoints;
				manifold.numPoints = count;
				int rolling = nextRolling;
				for (int k = 0; k < count; ++k)
				{
					const int index = numPoints + k;
					caliber::ContactPointRows& point = mt->points[index];
					point = mt->planned[i * MANIFOLD_CACHE_SIZE + k];
					point.contactRow = contactBase + index;
					point.firstFrictionRow = frictionBase + index * frictionRowsPerContact;
					point.firstRollingRow = rolling;
					rolling += caliber::rollingRowsOf(*point.cp);
				}
				numPoints += count;
				nextRolling += mt->plannedRolling[i];
			}
		}
	}
};

struct FillPointRows : public btIParallelForBody
{
	caliber::ContactRowPools pools;
	const caliber::ContactPointRows* points;
	const btContactSolverInfo* info;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) caliber::fillContactPointRows(pools, points[i], *info);
	}
};

// Bodies per task of the warm starts.
const int kBodiesPerWarmStartTask = 128;

// Each body's warm-start impulses, in the order the serial setup applies them (point by point: the
// normal row, then the friction rows). A body's velocity changes are sums, and their terms come in the
// same order, so the bits are the serial loop's; bodies are independent, so they go to the threads: in
// slices of the runs (BodySlices) when the bodies are listed by run, else by index.
struct ApplyWarmStarts : public btIParallelForBody
{
	const MtSolverScratch* mt;
	caliber::ContactRowPools pools;
	int frictionRowsPerContact;
	int contactBase, frictionBase;  // the rows of point i: contactBase + i, frictionBase + i * frictionRowsPerContact
	BodySlices slices;

	void forLoop(int iBegin, int iEnd) const override
	{
		if (slices.runs == 0)
		{
			for (int b = iBegin; b < iEnd; ++b) apply(b);
			return;
		}
		for (int c = iBegin; c < iEnd; ++c)
		{
			int begin, end;
			slices.slice(c, begin, end);
			for (int k = begin; k < end; ++k) apply(slices.bodies[k]);
		}
	}

	void apply(int b) const
	{
		const btSolverConstraint* contacts = &(*pools.contacts)[contactBase];
		const btSolverConstraint* friction = frictionRowsPerContact ? &(*pools.friction)[frictionBase] : 0;
		btSolverBody& body = (*pools.bodies)[b];
		for (int k = mt->warmStartFirst[b]; k < mt->warmStartFirst[b + 1]; ++k)
		{
			const int code = mt->warmStarts[k];
			const MtSolverScratch::RowManifold& manifold = mt->rowManifolds[code >> 1];
			// The manifold's rows: its points' normal rows, and their friction rows, follow each other.
			const btSolverConstraint* row = contacts + manifold.firstPoint;
			const btSolverConstraint* rowEnd = row + manifold.numPoints;
			const btSolverConstraint* frictionRow = friction + manifold.firstPoint * frictionRowsPerContact;
			if (code & 1)
				for (; row != rowEnd; ++row)
				{
					body.applyImpulse(row->m_contactNormal2, row->m_angularComponentB, row->m_appliedImpulse);
					for (int f = 0; f < frictionRowsPerContact; ++f, ++frictionRow)
						body.applyImpulse(frictionRow->m_contactNormal2, frictionRow->m_angularComponentB,
						                  frictionRow->m_appliedImpulse);
				}
			else
				for (; row != rowEnd; ++row)
				{
					body.applyImpulse(row->m_contactNormal1, row->m_angularComponentA, row->m_appliedImpulse);
					for (int f = 0; f < frictionRowsPerContact; ++f, ++frictionRow)
						body.applyImpulse(frictionRow->m_contactNormal1, frictionRow->m_angularComponentA,
						                  frictionRow->m_appliedImpulse);
				}
		}
	}
};

// Chunks of the manifolds whose per-body lists are counted and written on the threads. Fixed (not the
// thread count), so the lists do not depend on the threads.
const int kWarmStartChunks = 4;

// The manifolds of warm-start chunk c.
inline void warmStartChunk(int c, int numRowManifolds, int& begin, int& end)
{
	begin = int((long long)numRowManifolds * c / kWarmStartChunks);
	end = int((long long)numRowManifolds * (c + 1) / kWarmStartChunks);
}

// Each chunk's entries per body (count) and then, from the cursors the calling thread made of them, the
// entries themselves (write): a chunk touches only its own row of the cursors and its own places.
struct BuildWarmStartLists : public btIParallelForBody
{
	MtSolverScratch* mt;
	int numBodies;
	int fixedBodyId;
	bool write;

	void forLoop(int iBegin, int iEnd) const override
	{
		const int numRowManifolds = mt->rowManifolds.size();
		for (int c = iBegin; c < iEnd; ++c)
		{
			int* cursor = &mt->warmStartChunkCursor[c * numBodies];
			int begin, end;
			warmStartChunk(c, numRowManifolds, begin, end);
			if (!write)
			{
				memset(cursor, 0, sizeof(int) * size_t(numBodies));
				for (int m = begin; m < end; ++m)
				{
					const MtSolverScratch::RowManifold& manifold = mt->rowManifolds[m];
					if (manifold.bodyA != fixedBodyId) ++cursor[manifold.bodyA];
					if (manifold.bodyB != fixedBodyId) ++cursor[manifold.bodyB];
				}
				continue;
			}
			int* entries = mt->warmStarts.size() ? &mt->warmStarts[0] : 0;
			for (int m = begin; m < end; ++m)
			{
				const MtSolverScratch::RowManifold& manifold = mt->rowManifolds[m];
				if (manifold.bodyA != fixedBodyId) entries[cursor[manifold.bodyA]++] = m << 1;
				if (manifold.bodyB != fixedBodyId) entries[cursor[manifold.bodyB]++] = m << 1 | 1;
			}
		}
	}
};

// The warm starts of the planned points (mt.points). A manifold's points all have its two bodies and
// follow each other in the point list, so a body's points in order are its manifolds' points in order:
// the lists hold manifolds (a quarter of the entries, from the small rowManifolds array). The fixed entry
// takes none: its impulses would add zeros to zeros (it has no mass and no inertia to turn). The lists are
// a counting sort by body, in chunks of manifolds on the threads: a body's entries from chunk 0 come
// first, in manifold order, then chunk 1's, ..., so each list is in manifold order.
void applyWarmStartsByBody(MtSolverScratch& mt, const caliber::ContactRowPools& pools, int frictionRowsPerContact,
                           int contactBase, int frictionBase, int fixedBodyId)
{
	const int numBodies = pools.bodies->size();
	caliber::resizeScratch(mt.warmStartFirst, numBodies + 1);
	caliber::resizeScratch(mt.warmStartChunkCursor, kWarmStartChunks * numBodies);
	BuildWarmStartLists lists;
	lists.mt = &mt;
	lists.numBodies = numBodies;
	lists.fixedBodyId = fixedBodyId;
	lists.write = false;
	btParallelFor(0, kWarmStartChunks, 1, lists);
	int next = 0;
	for (int b = 0; b < numBodies; ++b)
	{
		mt.warmStartFirst[b] = next;
		for (int c = 0; c < kWarmStartChunks; ++c)
		{
			int& cursor = mt.warmStartChunkCursor[c * numBodies + b];
			const int count = cursor;
			cursor = next;
			next += count;
		}
	}
	mt.warmStartFirst[numBodies] = next;
	caliber::resizeScratch(mt.warmStarts, next);
	lists.write = true;
	btParallelFor(0, kWarmStartChunks, 1, lists);
	ApplyWarmStarts apply;
	apply.mt = &mt;
	apply.pools = pools;
	apply.frictionRowsPerContact = frictionRowsPerContact;
	apply.contactBase = contactBase;
	apply.frictionBase = frictionBase;
	apply.slices = BodySlices::of(mt, numBodies, kBodiesPerWarmStartTask);
	if (apply.slices.runs)
		btParallelFor(0, apply.slices.count(), 1, apply);
	else
		btParallelFor(0, numBodies, kBodiesPerWarmStartTask, apply);
}

// Asks for count consecutive rows from first.
inline void prefetchRows(const btSolverConstraint* first, int count)
{
#if defined(__GNUC__)
	const char* bytes = reinterpret_cast<const char*>(first);
	const int size = int(sizeof(btSolverConstraint)) * count;
	for (int offset = 0; offset < size; offset += 64) __builtin_prefetch(bytes + offset);
#else
	(void)first;
	(void)count;
#endif
}

// How many entries of batchesByRun from k (before end) name consecutive batches: the wide rows' fill and
// store take them in one call (all of them on one thread, where the order is the batches' own).
inline int consecutiveBatches(const btAlignedObjectArray<int>& batchesByRun, int k, int end)
{
	int span = 1;
	while (k + span < end && batchesByRun[k + span] == batchesByRun[k] + span) ++span;
	return span;
}

// Batches per task of the parallel wide-row fill.
const int kBatchesPerWideFillTask = 4;

// The wide rows of the batches (each batch's own groups and blocks: any order, any thread).
struct FillWideRows : public btIParallelForBody
{
	MtSolverScratch* mt;
	const btAlignedObjectArray<int>* manifoldFirstRow;
	unsigned int solveCount;
	const btSolverBody* bodies;
	const btConstraintArray* contacts;
	const btConstraintArray* friction;
	std::atomic<bool>* fits;  // cleared when a row cannot be held by the blocks

	void forLoop(int iBegin, int iEnd) const override
	{
		bool allFit = true;
		for (int k = iBegin, span; k < iEnd; k += span)
		{
			const int b = mt->batchesByRun[k];
			span = consecutiveBatches(mt->batchesByRun, k, iEnd);
			allFit = mt->wideRows.fill(b, b + span, mt->orderedManifolds, mt->batchManifoldBegin, *manifoldFirstRow,
			                           mt->batchPaddingBody, solveCount, bodies, *contacts, *friction) &&
			         allFit;
		}
		if (!allFit) fits->store(false, std::memory_order_relaxed);
	}
};

// The wide blocks' impulses into their rows (each batch its own rows: any order, any thread).
struct StoreWideImpulses : public btIParallelForBody
{
	caliber::WideContactRows* wide;
	const btAlignedObjectArray<int>* batchesByRun;
	btConstraintArray* contacts;
	btConstraintArray* friction;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int k = iBegin, span; k < iEnd; k += span)
		{
			span = consecutiveBatches(*batchesByRun, k, iEnd);
			wide->storeImpulses((*batchesByRun)[k], (*batchesByRun)[k] + span, *contacts, *friction);
		}
	}
};

// One sweep over a batch of contact rows: normals, then their friction, then their rolling rows.
struct BatchSweep : public btIParallelForBody
{
	const btBatchedConstraints* batched;
	btSolverBody* bodies;
	btConstraintArray* contacts;
	btConstraintArray* friction;
	btConstraintArray* rolling;
	MtSolverScratch* scratch;
	int firstBatch;
	int frictionRowsPerContact;
	bool reverse;
	int pass;                 // 0: normal rows, 1: friction and rolling rows
	btScalar* batchResidual;  // per batch of the phase

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int b = iBegin; b < iEnd; ++b)
			batchResidual[b] =
			    scratch->wide ? sweepWideBatch(firstBatch + b) : sweepBatch(batched->m_batches[firstBatch + b]);
	}

	btScalar sweepWideBatch(int batch) const
	{
		caliber::WideContactRows& wide = scratch->wideRows;
		// The rolling rows read their contact rows' impulses during the sweeps; otherwise the impulses go to
		// the rows once, after the last sweep (storing them block by block costs a cache line per row).
		const bool rollingRows = rolling->size() > 0;
		if (pass == 0) return wide.sweepNormal(batch, reverse, bodies, rollingRows ? contacts : 0);
		return sweepRolling(batched->m_batches[batch], wide.sweepFriction(batch, reverse, bodies, 0));
	}

	btScalar sweepBatch(const btBatchedConstraints::Range& batch) const
	{
		btScalar residual = btScalar(0);
		const int count = batch.end - batch.begin;
		const int* rows = &batched->m_constraintIndices[0];
		// A batch jumps from manifold to manifold over the row pools, which the hardware prefetcher does not
		// follow: rows are asked for a manifold ahead.
		const int kAhead = 4;
		if (pass == 0)
		{
			for (int k = 0; k < count; ++k)
			{
				if (k + kAhead < count)
					prefetchRows(&(*contacts)[rows[batch.begin + (reverse ? count - 1 - k - kAhead : k + kAhead)]], 1);
				btSolverConstraint& row = (*contacts)[rows[batch.begin + (reverse ? count - 1 - k : k)]];
				residual += caliber::resolveRow(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row,
				                                row.m_lowerLimit, row.m_upperLimit);
			}
			return residual;
		}
		for (int k = 0; k < count; ++k)
		{
			if (k + kAhead < count)
			{
				const int ahead = rows[batch.begin + (reverse ? count - 1 - k - kAhead : k + kAhead)];
				prefetchRows(&(*friction)[ahead * frictionRowsPerContact], frictionRowsPerContact);
			}
			const int j = rows[batch.begin + (reverse ? count - 1 - k : k)];
			for (int f = 0; f < frictionRowsPerContact; ++f)
				residual += caliber::solveFrictionRow(bodies, *contacts, *friction, j * frictionRowsPerContact + f);
		}
		return sweepRolling(batch, residual);
	}

	// The rolling rows of a batch's contacts, after their friction rows.
	btScalar sweepRolling(const btBatchedConstraints::Range& batch, btScalar residual) const
	{
		if (rolling->size() == 0) return residual;
		const int count = batch.end - batch.begin;
		const int* rows = &batched->m_constraintIndices[0];
		for (int k = 0; k < count; ++k)
		{
			const int j = rows[batch.begin + k];
			const btScalar normalImpulse = (*contacts)[j].m_appliedImpulse;
			if (!(normalImpulse > btScalar(0))) continue;
			for (int r = scratch->rollingStart[j]; r < scratch->rollingStart[j + 1]; ++r)
			{
				btSolverConstraint& row = (*rolling)[scratch->rollingRows[r]];
				const btScalar bound = row.m_friction * normalImpulse;
				residual +=
				    caliber::resolveRow(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row, -bound, bound);
			}
		}
		return residual;
	}
};

#if defined(__SSE2__) || defined(__x86_64__) || defined(_M_X64)
inline void spinPause() { _mm_pause(); }
#else
inline void spinPause() {}
#endif

// Waits until this loop has finished an item: a few pauses, then yields (the machine may have more threads
// than cores, and the thread that claimed the item may be waiting for a core).
void waitUntilDone(const MtSolverScratch::DoneFlag& flag, unsigned loop)
{
	for (int attempt = 0; flag.loop.load(std::memory_order_acquire) != loop; ++attempt)
	{
		if (attempt < 64)
			spinPause();
		else
			std::this_thread::yield();
	}
}

// One iteration's sweep of the batches in one parallel loop. The items (a run of a colour's batches in one
// pass) are listed in the sweep's order; task t runs, in that order, the items given to it
// (caliber::listSweepItems: each colour cut into runs in task order, balanced by rows), so that from colour
// to colour a thread mostly meets the same region of the island, in its own cache. Before each batch it waits until the batches it
// depends on are finished, and when one of them belongs to an item no task has claimed yet, it claims and
// runs that item itself. Then it runs whatever no task has claimed. Why no task waits forever, whatever the
// scheduler: a task waits only for an item another task has claimed and runs; the item a task waits in is
// the earliest of those it is running (it runs a claimed dependency, always an earlier item, inside the
// item that needs it), and waits for an earlier item still; so the waits go to ever earlier items, and the
// earliest item being run waits for nothing.
struct DependentSweep : public btIParallelForBody
{
	const BatchSweep* passes[2];  // normal rows, friction rows; residuals go to the item's place
	MtSolverScratch* mt;
	const btAlignedObjectArray<MtSolverScratch::SweepItem>* items;  // the sweep's direction's
	const btAlignedObjectArray<int>* itemOfBatch;
	caliber::BatchDependencies::Sweep sweeps[2];
	int numBatches;
	unsigned loop;

	void forLoop(int iBegin, int iEnd) const override
	{
		const int numItems = items->size();
		for (int lane = iBegin; lane < iEnd; ++lane)
			for (int i = 0; i < numItems; ++i)
				if ((*items)[i].run == lane && claim(i)) run(i);
		for (int i = 0; i < numItems; ++i)
			if (claim(i)) run(i);
	}

	bool claim(int item) const
	{
		std::atomic<unsigned>& claimed = mt->itemClaimed[item].loop;
		return claimed.load(std::memory_order_relaxed) != loop &&
		       claimed.exchange(loop, std::memory_order_relaxed) != loop;
	}

	void run(int i) const
	{
		const MtSolverScratch::SweepItem item = (*items)[i];
		const caliber::BatchDependencies::Sweep sweep = sweeps[item.pass];
		MtSolverScratch::DoneFlag* done = &mt->itemDone[0];
		for (int b = item.batchBegin; b < item.batchEnd; ++b)
		{
			const int* dependencies = mt->dependenciesListed ? mt->dependencies.list(sweep, b) : nullptr;
			const int count = mt->dependenciesListed ? mt->dependencies.count(sweep, b) : 0;
			for (int d = 0; d < count; ++d)
			{
				const MtSolverScratch::DoneFlag& flag = done[dependencies[d]];
				if (flag.loop.load(std::memory_order_acquire) == loop) continue;
				const int owner = (*itemOfBatch)[dependencies[d]];
				if (claim(owner))
					run(owner);  // an earlier item: it finishes the dependency
				else
					waitUntilDone(flag, loop);
			}
			passes[item.pass]->forLoop(b, b + 1);
			done[item.pass * numBatches + b].loop.store(loop, std::memory_order_release);
		}
	}
};

// The items of the sweep in one direction, balanced by rows (caliber::listSweepItems).
void listSweepItems(MtSolverScratch& mt, const btBatchedConstraints& batched, bool reverse, int numThreads)
{
	caliber::listSweepItems(batched, reverse, numThreads, mt.sweepItems[reverse ? 1 : 0], mt.itemOfBatch[reverse ? 1 : 0]);
	mt.itemThreads[reverse ? 1 : 0] = numThreads;
}

// mt.batchesByRun: each batch goes with the run that sweeps it forwards, normal rows (the runs of the other
// pass and direction cut each colour the same way but for the balance's carry from colour to colour, a batch
// or so), or with the loop per colour's chunk (one chunk per thread) when the sweep waits per colour. The
// pool hands each thread a contiguous share of a loop's chunks, the calling thread the first, so a loop over
// this order gives thread t about the batches of run t. Which thread runs a batch changes no result.
void listBatchesByRun(MtSolverScratch& mt, const btBatchedConstraints& batched, int numThreads)
{
	const int numBatches = batched.m_batches.size();
	caliber::resizeScratch(mt.batchesByRun, numBatches);
	const int tasks = btMin(btMax(numThreads, 1), int(BT_MAX_THREAD_COUNT));
	int runStart[BT_MAX_THREAD_COUNT + 1] = {};
	auto runOf = [&](int batch)
	{
		if (mt.dependentSweep) return mt.sweepItems[0][mt.itemOfBatch[0][batch]].run;
		for (int k = 0; k < batched.m_phases.size(); ++k)
		{
			const btBatchedConstraints::Range& phase = batched.m_phases[k];
			if (batch < phase.begin || batch >= phase.end) continue;
			const int grain = (phase.end - phase.begin + tasks - 1) / tasks;
			return (batch - phase.begin) / grain;
		}
		return 0;
	};
	if (tasks == 1 || (mt.dependentSweep && mt.itemThreads[0] != numThreads))
	{
		for (int b = 0; b < numBatches; ++b) mt.batchesByRun[b] = b;
		mt.batchRun.resize(0);
		return;
	}
	// A counting sort by run.
	caliber::resizeScratch(mt.batchRun, numBatches);
	for (int b = 0; b < numBatches; ++b)
	{
		const int run = btMin(runOf(b), tasks - 1);
		mt.batchRun[b] = run;
		++runStart[run + 1];
	}
	for (int t = 0; t < tasks; ++t) runStart[t + 1] += runStart[t];
	for (int b = 0; b < numBatches; ++b) mt.batchesByRun[runStart[mt.batchRun[b]]++] = b;
}

// mt.bodiesByRun and mt.bodyRunStart for the solver bodies [0, numSolverBodies) (see MtSolverScratch), from
// the batches' runs (listBatchesByRun); nothing listed when the batches have no runs. Which thread warms
// or writes back a body changes no result: each body's sums are its own, in its own order.
void listBodiesByRun(MtSolverScratch& mt, const btBatchedConstraints& batched, int numSolverBodies, int fixedBodyId,
                     int numThreads)
{
	const int numBatches = batched.m_batches.size();
	const int tasks = btMin(btMax(numThreads, 1), int(BT_MAX_THREAD_COUNT));
	mt.bodyRunStart.resize(0);
	if (tasks == 1 || numSolverBodies == 0 || mt.batchRun.size() != numBatches ||
	    mt.batchManifoldBegin.size() != numBatches + 1)
		return;
	caliber::assignScratch(mt.bodyRun, numSolverBodies, -1);
	caliber::assignScratch(mt.bodyVotes, numSolverBodies, 0);
	int* bodyRun = &mt.bodyRun[0];
	int* votes = &mt.bodyVotes[0];
	// A majority vote in one pass (Boyer and Moore's): a run that holds more than half of a body's
	// manifolds wins; without one, some run that holds a share.
	auto vote = [&](int body, int run)
	{
		if (body == fixedBodyId) return;
		if (votes[body] == 0)
		{
			bodyRun[body] = run;
			votes[body] = 1;
		}
		else
			votes[body] += bodyRun[body] == run ? 1 : -1;
	};
	for (int b = 0; b < numBatches; ++b)
	{
		const int run = mt.batchRun[b];
		for (int i = mt.batchManifoldBegin[b]; i < mt.batchManifoldBegin[b + 1]; ++i)
		{
			const MtSolverScratch::RowManifold& manifold = mt.rowManifolds[mt.orderedManifolds[i]];
			vote(manifold.bodyA, run);
			vote(manifold.bodyB, run);
		}
	}
	caliber::assignScratch(mt.bodyRunStart, tasks + 1, 0);
	int* runStart = &mt.bodyRunStart[0];
	for (int body = 0; body < numSolverBodies; ++body)
	{
		if (bodyRun[body] < 0) bodyRun[body] = int((long long)body * tasks / numSolverBodies);
		++runStart[bodyRun[body] + 1];
	}
	for (int t = 0; t < tasks; ++t) runStart[t + 1] += runStart[t];
	caliber::resizeScratch(mt.bodiesByRun, numSolverBodies);
	for (int body = 0; body < numSolverBodies; ++body) mt.bodiesByRun[runStart[bodyRun[body]]++] = body;
	// The cursors ended at the next run's start: back to each run's own.
	for (int t = tasks; t > 0; --t) runStart[t] = runStart[t - 1];
	runStart[0] = 0;
}

// The sweep of one iteration with DependentSweep; adds the batches' residuals to residual as the loop per
// colour adds them (pass by pass, colour by colour in the sweep's order, batch by batch).
btScalar sweepWithDependencies(MtSolverScratch& mt, const BatchSweep& sweep, bool reverse, int numThreads,
                               btScalar residual)
{
	const btBatchedConstraints& batched = *sweep.batched;
	const int numBatches = batched.m_batches.size();
	const int numPhases = batched.m_phases.size();
	if (mt.itemThreads[reverse ? 1 : 0] != numThreads) listSweepItems(mt, batched, reverse, numThreads);
	const btAlignedObjectArray<MtSolverScratch::SweepItem>& items = mt.sweepItems[reverse ? 1 : 0];
	caliber::resizeScratch(mt.batchResidual, 2 * numBatches);
	BatchSweep normal = sweep, friction = sweep;
	normal.pass = 0;
	normal.firstBatch = 0;
	normal.batchResidual = &mt.batchResidual[0];
	friction.pass = 1;
	friction.firstBatch = 0;
	friction.batchResidual = &mt.batchResidual[numBatches];
	if (mt.itemClaimed.size() < items.size()) mt.itemClaimed.resize(items.size());
	if (++mt.sweepLoop == 0)
	{
		// After 2^32 loops: no flag may hold the new loop's number from long ago.
		for (int i = 0; i < mt.itemDone.size(); ++i) mt.itemDone[i].loop.store(0, std::memory_order_relaxed);
		for (int i = 0; i < mt.itemClaimed.size(); ++i) mt.itemClaimed[i].loop.store(0, std::memory_order_relaxed);
		mt.sweepLoop = 1;
	}
	DependentSweep body;
	body.passes[0] = &normal;
	body.passes[1] = &friction;
	body.mt = &mt;
	body.items = &items;
	body.itemOfBatch = &mt.itemOfBatch[reverse ? 1 : 0];
	body.sweeps[0] = reverse ? caliber::BatchDependencies::kBackwardNormal : caliber::BatchDependencies::kForwardNormal;
	body.sweeps[1] =
	    reverse ? caliber::BatchDependencies::kBackwardFriction : caliber::BatchDependencies::kForwardFriction;
	body.numBatches = numBatches;
	body.loop = mt.sweepLoop;
	btParallelFor(0, numThreads, 1, body);
	for (int pass = 0; pass < 2; ++pass)
		for (int k = 0; k < numPhases; ++k)
		{
			const btBatchedConstraints::Range& phase =
			    batched.m_phases[batched.m_phaseOrder[reverse ? numPhases - 1 - k : k]];
			for (int b = phase.begin; b < phase.end; ++b) residual += mt.batchResidual[pass * numBatches + b];
		}
	return residual;
}
}  // namespace

namespace
{
// The colours, level by level up the stacks (btContactColouring.h; the fixed entry joins any colour),
// and each colour's manifolds and rows.
void colourManifolds(MtSolverScratch& mt, const btSolverBody* bodies, int numSolverBodies, int fixedBodyId)
{
	const int numRowManifolds = mt.rowManifolds.size();
	static_assert(sizeof(MtSolverScratch::RowManifold) % sizeof(int) == 0 &&
	                  offsetof(MtSolverScratch::RowManifold, bodyB) ==
	                      offsetof(MtSolverScratch::RowManifold, bodyA) + sizeof(int),
	              "the colouring reads a manifold's two bodies as consecutive ints");
	mt.colouring.colour(&mt.rowManifolds[0].bodyA, int(sizeof(MtSolverScratch::RowManifold) / sizeof(int)),
	                    numRowManifolds, bodies, numSolverBodies, fixedBodyId,
	                    caliber::solveUpDirection(bodies, numSolverBodies));
	const int numColours = mt.colouring.numColours();
	const btAlignedObjectArray<int>& manifoldColour = mt.colouring.manifoldColour();
	caliber::assignScratch(mt.colourCount, numColours, 0);
	caliber::assignScratch(mt.colourRows, numColours, 0);
	for (int m = 0; m < numRowManifolds; ++m)
	{
		++mt.colourCount[manifoldColour[m]];
		mt.colourRows[manifoldColour[m]] += mt.rowManifolds[m].numPoints;
	}
}

// Manifolds colour by colour, and within a colour by their first moving body (two stable counting sorts):
// a run of batches then holds the bodies of one region of the island (see the sweep).
void orderManifoldsByColourAndBody(MtSolverScratch& mt, int numSolverBodies, int fixedBodyId)
{
	const int numRowManifolds = mt.rowManifolds.size();
	caliber::assignScratch(mt.bodyOrder, numSolverBodies + 1, 0);
	for (int m = 0; m < numRowManifolds; ++m) ++mt.bodyOrder[firstMovingBody(mt.rowManifolds[m], fixedBodyId) + 1];
	for (int b = 0; b < numSolverBodies; ++b) mt.bodyOrder[b + 1] += mt.bodyOrder[b];
	caliber::resizeScratch(mt.byBody, numRowManifolds);
	for (int m = 0; m < numRowManifolds; ++m)
		mt.byBody[mt.bodyOrder[firstMovingBody(mt.rowManifolds[m], fixedBodyId)]++] = m;
	const int numColours = mt.colourCount.size();
	caliber::resizeScratch(mt.colourCursor, numColours);
	int start = 0;
	for (int c = 0; c < numColours; ++c)
	{
		mt.colourCursor[c] = start;
		start += mt.colourCount[c];
	}
	const btAlignedObjectArray<int>& manifoldColour = mt.colouring.manifoldColour();
	caliber::resizeScratch(mt.orderedManifolds, numRowManifolds);
	for (int k = 0; k < numRowManifolds; ++k)
	{
		const int m = mt.byBody[k];
		mt.orderedManifolds[mt.colourCursor[manifoldColour[m]]++] = m;
	}
}

// Batches: whole manifolds, at least minBatchSize rows, and about a sixteenth of the colour, so that every
// thread finds work; a colour's batches but its last hold whole groups of the wide sweep (eight manifolds:
// a group with fewer sweeps padding lanes). One phase per colour.
// Writes the row lists of batches [iBegin, iEnd): each batch's place in the list is known beforehand (its
// rows are its manifolds' rows), so any split of the batches writes the same list.
struct WriteBatchRows : public btIParallelForBody
{
	const MtSolverScratch* mt;
	const caliber::SolverScratch* scratch;
	btBatchedConstraints* batched;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int k = iBegin; k < iEnd; ++k)
		{
			const int b = mt->batchesByRun[k];
			const int firstManifold = mt->batchManifoldBegin[b];
			writeBatchRows(&mt->orderedManifolds[firstManifold], mt->batchManifoldBegin[b + 1] - firstManifold,
			               scratch->manifoldFirstRow, scratch->solveCount,
			               &batched->m_constraintIndices[batched->m_batches[b].begin]);
		}
	}
};

const int kManifoldsPerWideGroup = 8;

// The batches' manifold and row ranges (their row lists: writeColourBatchRows).
void planColourBatches(MtSolverScratch& mt, int minBatchSize, btBatchedConstraints& batched)
{
	batched.m_constraintIndices.resize(0);
	batched.m_batches.resize(0);
	batched.m_phases.resize(0);
	batched.m_phaseGrainSize.resize(0);
	batched.m_phaseOrder.resize(0);
	int nextManifold = 0;
	int nextRow = 0;
	mt.batchManifoldBegin.resize(0);
	mt.itemThreads[0] = mt.itemThreads[1] = 0;  // new batches: the sweep's items are listed again
	for (int c = 0; c < mt.colourCount.size(); ++c)
	{
		if (mt.colourCount[c] == 0) continue;
		const int phaseBegin = batched.m_batches.size();
		const int targetRows = btMax(btMax(1, minBatchSize), (mt.colourRows[c] + 15) / 16);
		int batchRows = 0;
		int batchFirstManifold = nextManifold;
		for (int k = 0; k < mt.colourCount[c]; ++k)
		{
			batchRows += mt.rowManifolds[mt.orderedManifolds[nextManifold++]].numPoints;
			const bool wholeGroups = (nextManifold - batchFirstManifold) % kManifoldsPerWideGroup == 0;
			if ((batchRows < targetRows || !wholeGroups) && k + 1 < mt.colourCount[c]) continue;
			mt.batchManifoldBegin.push_back(batchFirstManifold);
			batched.m_batches.push_back(btBatchedConstraints::Range(nextRow, nextRow + batchRows));
			nextRow += batchRows;
			batchFirstManifold = nextManifold;
			batchRows = 0;
		}
		batched.m_phaseOrder.push_back(batched.m_phases.size());
		batched.m_phases.push_back(btBatchedConstraints::Range(phaseBegin, batched.m_batches.size()));
		batched.m_phaseGrainSize.push_back(1);
	}
	mt.batchManifoldBegin.push_back(nextManifold);
	caliber::resizeScratch(batched.m_constraintIndices, nextRow);
}

// The batches' row lists, batch by batch on the threads.
void writeColourBatchRows(MtSolverScratch& mt, const caliber::SolverScratch& scratch, btBatchedConstraints& batched)
{
	WriteBatchRows write;
	write.mt = &mt;
	write.scratch = &scratch;
	write.batched = &batched;
	btParallelFor(0, batched.m_batches.size(), kBatchesPerWideFillTask, write);
}

// Manifolds per block of the serial solver's contact order (its kInterleave), and blocks per task.
const int kOrderBlockManifolds = 8;
const int kOrderBlocksPerTask = 16;

// The serial solver's contact order (btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup),
// which the split-impulse pass follows: blocks of consecutive manifolds, interleaved as in a batch. A
// block's rows are its manifolds' rows, so its place in the order is known and any split writes the same.
// Each index of the loop is a chunk of kOrderBlocksPerTask blocks, which also lists its rows with a push
// target in that order (the scan the push pass would make, chunk by chunk): joined in chunk order, the
// lists are the push pass's list, whatever the split of the chunks.
struct WriteContactOrder : public btIParallelForBody
{
	const caliber::SolverScratch* scratch;
	int* order;
	const int* manifolds;  // 0, 1, 2, ...
	const btConstraintArray* contacts;
	MtSolverScratch::PushChunk* pushChunks;

	void forLoop(int iBegin, int iEnd) const override
	{
		const btAlignedObjectArray<int>& manifoldFirstRow = scratch->manifoldFirstRow;
		const int numManifolds = manifoldFirstRow.size() - 1;
		for (int chunk = iBegin; chunk < iEnd; ++chunk)
		{
			const int first = chunk * kOrderBlocksPerTask * kOrderBlockManifolds;
			const int end = btMin(first + kOrderBlocksPerTask * kOrderBlockManifolds, numManifolds);
			int* chunkOrder = order + manifoldFirstRow[first] - manifoldFirstRow[0];
			writeBatchRows(manifolds + first, end - first, manifoldFirstRow, scratch->solveCount, chunkOrder);
			btAlignedObjectArray<int>& pushRows = pushChunks[chunk].rows;
			pushRows.resize(0);
			const int numRows = manifoldFirstRow[end] - manifoldFirstRow[first];
			for (int k = 0; k < numRows; ++k)
				if ((*contacts)[chunkOrder[k]].m_rhsPenetration != btScalar(0)) pushRows.push_back(chunkOrder[k]);
		}
	}
};

// Each batch's rows of the fixed entry are pointed at the batch's own copy of it (see the file comment):
// contact and friction rows by batch, on the threads (a row belongs to one batch, so any split of the
// batches writes the same), then rolling rows after their contact row, on the calling thread.
struct GiveBatchesFixedBodyCopies : public btIParallelForBody
{
	const btBatchedConstraints* batched;
	const int* batchesByRun;
	int fixedBodyId, firstCopy, frictionRows;
	btConstraintArray* contacts;
	btConstraintArray* friction;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int k = iBegin; k < iEnd; ++k)
		{
			const int b = batchesByRun[k];
			const int copy = firstCopy + b;
			for (int i = batched->m_batches[b].begin; i < batched->m_batches[b].end; ++i)
			{
				const int j = batched->m_constraintIndices[i];
				btSolverConstraint& row = (*contacts)[j];
				if (row.m_solverBodyIdA == fixedBodyId) row.m_solverBodyIdA = copy;
				if (row.m_solverBodyIdB == fixedBodyId) row.m_solverBodyIdB = copy;
				for (int f = 0; f < frictionRows; ++f)
				{
					btSolverConstraint& frictionRow = (*friction)[j * frictionRows + f];
					if (frictionRow.m_solverBodyIdA == fixedBodyId) frictionRow.m_solverBodyIdA = copy;
					if (frictionRow.m_solverBodyIdB == fixedBodyId) frictionRow.m_solverBodyIdB = copy;
				}
			}
		}
	}
};

void giveBatchesFixedBodyCopies(const btBatchedConstraints& batched, const int* batchesByRun, int fixedBodyId,
                                int firstCopy, int frictionRows, btConstraintArray& contacts,
                                btConstraintArray& friction, btConstraintArray& rolling)
{
	GiveBatchesFixedBodyCopies give;
	give.batched = &batched;
	give.batchesByRun = batchesByRun;
	give.fixedBodyId = fixedBodyId;
	give.firstCopy = firstCopy;
	give.frictionRows = frictionRows;
	give.contacts = &contacts;
	give.friction = &friction;
	btParallelFor(0, batched.m_batches.size(), kBatchesPerWideFillTask, give);
	for (int r = 0; r < rolling.size(); ++r)
	{
		btSolverConstraint& row = rolling[r];
		const btSolverConstraint& contact = contacts[row.m_frictionIndex];
		if (row.m_solverBodyIdA == fixedBodyId) row.m_solverBodyIdA = contact.m_solverBodyIdA;
		if (row.m_solverBodyIdB == fixedBodyId) row.m_solverBodyIdB = contact.m_solverBodyIdB;
	}
}

// What the coloured sweep needs of the manifolds alone, all serial: the colours, the manifolds in colour and
// body order, the batches' ranges, the sweep's items in both directions for numThreads threads and, for the sweep without a wait per colour at more than one thread, each
// body's batches in order (the lists themselves are made on the threads later). convertContacts runs it as
// the first chunk of the contact rows' fill, so that one thread makes it while the others fill rows instead
// of the calling thread making it alone after the fill: it reads the manifolds' bodies and point counts and
// the solver bodies' poses and gravity, which the fill only reads, and writes only this scratch and the
// batches, which the fill does not touch. The same plan as made after the fill (nothing it reads changes).
void planColourSweep(MtSolverScratch& mt, const btSolverBody* bodies, int numSolverBodies, int fixedBodyId,
                     int minBatchSize, int numThreads, btBatchedConstraints& batched)
{
	colourManifolds(mt, bodies, numSolverBodies, fixedBodyId);
	orderManifoldsByColourAndBody(mt, numSolverBodies, fixedBodyId);
	planColourBatches(mt, minBatchSize, batched);
	if (mt.dependentSweep)
		for (int direction = 0; direction < 2; ++direction)
			listSweepItems(mt, batched, direction == 1, numThreads);
	listBatchesByRun(mt, batched, numThreads);
	listBodiesByRun(mt, batched, numSolverBodies, fixedBodyId, numThreads);
	if (mt.dependenciesListed)
	{
		static_assert(offsetof(MtSolverScratch::RowManifold, bodyB) ==
		                  offsetof(MtSolverScratch::RowManifold, bodyA) + sizeof(int),
		              "the dependencies read a manifold's two bodies as consecutive ints");
		mt.dependencies.sortBodies(&mt.batchManifoldBegin[0], batched.m_batches.size(), &mt.orderedManifolds[0],
		                           &mt.rowManifolds[0].bodyA, int(sizeof(MtSolverScratch::RowManifold) / sizeof(int)),
		                           numSolverBodies, fixedBodyId);
	}
	mt.plannedManifolds = mt.rowManifolds.size();
}

// The contact rows' fill, kPointsPerTask points per chunk after a first chunk that is planColourSweep.
// Nothing waits, so any scheduler and any split of the chunks give the same rows and the same plan.
struct FillPointRowsBesidePlan : public btIParallelForBody
{
	FillPointRows fill;
	int numPoints;
	MtSolverScratch* mt;
	const btSolverBody* bodies;
	int numSolverBodies;
	int fixedBodyId;
	int minBatchSize;
	int numThreads;
	btBatchedConstraints* batched;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int chunk = iBegin; chunk < iEnd; ++chunk)
		{
			if (chunk == 0)
			{
				planColourSweep(*mt, bodies, numSolverBodies, fixedBodyId, minBatchSize, numThreads, *batched);
				continue;
			}
			const int first = (chunk - 1) * kPointsPerTask;
			fill.forLoop(first, btMin(first + kPointsPerTask, numPoints));
		}
	}
};

// Rolling rows grouped by their contact row (counting sort).
void groupRollingRows(MtSolverScratch& mt, int numContacts, const btConstraintArray& rolling)
{
	// Without rolling rows the sweeps never read the groups.
	const int numRolling = rolling.size();
	if (numRolling == 0) return;
	caliber::assignScratch(mt.rollingStart, numContacts + 1, 0);
	for (int r = 0; r < numRolling; ++r) ++mt.rollingStart[rolling[r].m_frictionIndex + 1];
	for (int j = 0; j < numContacts; ++j) mt.rollingStart[j + 1] += mt.rollingStart[j];
	caliber::resizeScratch(mt.rollingRows, numRolling);
	caliber::assignScratch(mt.colourCursor, numContacts, 0);
	for (int r = 0; r < numRolling; ++r)
	{
		const int j = rolling[r].m_frictionIndex;
		mt.rollingRows[mt.rollingStart[j] + mt.colourCursor[j]++] = r;
	}
}
}  // namespace

btSequentialImpulseConstraintSolverMt::btSequentialImpulseConstraintSolverMt() : m_useBatching(false) {}

btSequentialImpulseConstraintSolverMt::~btSequentialImpulseConstraintSolverMt()
{
	caliber::sideTable<MtSolverScratch>().release(this);
}

void btSequentialImpulseConstraintSolverMt::convertContacts(btPersistentManifold** manifoldPtr, int numManifolds,
                                                            const btContactSolverInfo& infoGlobal)
{
	if (!m_useBatching)
	{
		btSequentialImpulseConstraintSolver::convertContacts(manifoldPtr, numManifolds, infoGlobal);
		return;
	}
	// The solver bodies, made in the serial order; which points get rows, on the threads; where their rows
	// go, in the serial order; the rows filled on the threads; the warm starts applied in the serial order.
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	MtSolverScratch& mt = mtScratchOf(*this);
	caliber::resizeScratch(mt.manifoldBodies, 2 * numManifolds);
	caliber::resizeScratch(mt.plannedCount, numManifolds);
	caliber::resizeScratch(mt.planned, numManifolds * MANIFOLD_CACHE_SIZE);
	caliber::resizeScratch(mt.plannedRolling, numManifolds);
	mt.rowManifolds.resize(0);
	if (numManifolds == 0) return;
	// The solver bodies of the manifolds' objects: those already in the pool found on the threads; the
	// others (objects outside the island's body list, such as static ones) made here in manifold order,
	// as getOrInitSolverBody would make them in a serial loop, so the pool comes out the same.
	FindManifoldBodies find;
	find.manifolds = manifoldPtr;
	find.mt = &mt;
	find.bodies = &m_tmpSolverBodyPool;
	btParallelFor(0, numManifolds, kManifoldsPerTask, find);
	for (int i = 0; i < numManifolds; ++i)
	{
		int* ids = &mt.manifoldBodies[2 * i];
		if (ids[0] != kLookUpSerially && ids[1] != kLookUpSerially) continue;
		btPersistentManifold* manifold = manifoldPtr[i];
		if (ids[0] == kLookUpSerially)
			ids[0] = getOrInitSolverBody(*const_cast<btCollisionObject*>(manifold->getBody0()), infoGlobal.m_timeStep);
		if (ids[1] == kLookUpSerially)
			ids[1] = getOrInitSolverBody(*const_cast<btCollisionObject*>(manifold->getBody1()), infoGlobal.m_timeStep);
	}
	PlanManifolds plan;
	plan.manifolds = manifoldPtr;
	plan.mt = &mt;
	plan.bodies = &m_tmpSolverBodyPool;
	plan.info = &infoGlobal;
	btParallelFor(0, numManifolds, kManifoldsPerTask, plan);

	// Where each manifold's points and rows go: counted chunk by chunk on the threads, the chunks summed in
	// order here, then written chunk by chunk on the threads (the serial setup's counts, manifold by
	// manifold).
	const int frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);
	const int contactBase = m_tmpSolverContactConstraintPool.size();
	const int frictionBase = m_tmpSolverContactFrictionConstraintPool.size();
	const int rollingBase = m_tmpSolverContactRollingFrictionConstraintPool.size();
	const int numChunks = (numManifolds + kManifoldsPerPlaceTask - 1) / kManifoldsPerPlaceTask;
	caliber::resizeScratch(mt.placeChunkStart, numChunks + 1);
	CountPlaces countPlaces;
	countPlaces.mt = &mt;
	countPlaces.numManifolds = numManifolds;
	btParallelFor(0, numChunks, 1, countPlaces);
	// placeChunkStart[c + 1] holds chunk c's own counts; the running sums make it chunk c + 1's start.
	MtSolverScratch::PlaceChunkStart total = {0, 0, 0};
	mt.placeChunkStart[0] = total;
	for (int c = 1; c <= numChunks; ++c)
	{
		MtSolverScratch::PlaceChunkStart& start = mt.placeChunkStart[c];
		total.points += start.points;
		total.rolling += start.rolling;
		total.rowManifolds += start.rowManifolds;
		start = total;
	}
	const int numPoints = total.points;
	const int firstManifoldRow = scratch.manifoldFirstRow.size();
	caliber::resizeScratch(scratch.manifoldFirstRow, firstManifoldRow + total.rowManifolds);
	caliber::resizeScratch(mt.rowManifolds, total.rowManifolds);
	caliber::resizeScratch(mt.rowManifoldSource, total.rowManifolds);
	caliber::resizeScratch(mt.points, numPoints);
	caliber::resizeScratch(m_tmpSolverContactConstraintPool, contactBase + numPoints);
	caliber::resizeScratch(m_tmpSolverContactFrictionConstraintPool, frictionBase + numPoints * frictionRowsPerContact);
	caliber::resizeScratch(m_tmpSolverContactRollingFrictionConstraintPool, rollingBase + total.rolling);
	if (numPoints == 0) return;
	PlacePoints place;
	place.mt = &mt;
	place.manifolds = manifoldPtr;
	place.manifoldFirstRow = &scratch.manifoldFirstRow[firstManifoldRow];
	place.numManifolds = numManifolds;
	place.contactBase = contactBase;
	place.frictionBase = frictionBase;
	place.rollingBase = rollingBase;
	place.frictionRowsPerContact = frictionRowsPerContact;
	btParallelFor(0, numChunks, 1, place);

	// The rows, and beside them the coloured sweep's plan (decided here for the set-up; the solver bodies
	// are all made, and the manifolds with rows are listed).
	FillPointRowsBesidePlan planAndFill;
	FillPointRows& fill = planAndFill.fill;
	fill.pools.bodies = &m_tmpSolverBodyPool;
	fill.pools.contacts = &m_tmpSolverContactConstraintPool;
	fill.pools.friction = &m_tmpSolverContactFrictionConstraintPool;
	fill.pools.rolling = &m_tmpSolverContactRollingFrictionConstraintPool;
	fill.points = &mt.points[0];
	fill.info = &infoGlobal;
	const int numThreads = solveThreads();
	mt.dependentSweep = !caliber::colourSweepBarriers();
	mt.dependenciesListed = mt.dependentSweep && numThreads > 1;
	planAndFill.numPoints = numPoints;
	planAndFill.numThreads = numThreads;
	planAndFill.mt = &mt;
	planAndFill.bodies = &m_tmpSolverBodyPool[0];
	planAndFill.numSolverBodies = m_tmpSolverBodyPool.size();
	planAndFill.fixedBodyId = m_fixedBodyId;
	planAndFill.minBatchSize = s_minBatchSize;
	planAndFill.batched = &m_batchedContactConstraints;
	btParallelFor(0, 1 + (numPoints + kPointsPerTask - 1) / kPointsPerTask, 1, planAndFill);
	if (!(infoGlobal.m_solverMode & SOLVER_USE_WARMSTARTING)) return;
	// By body on the threads, or point by point on one thread (the same bits either way).
	if (solveThreads() > 1)
		applyWarmStartsByBody(mt, fill.pools, frictionRowsPerContact, contactBase, frictionBase, m_fixedBodyId);
	else
		for (int i = 0; i < mt.points.size(); ++i)
			caliber::applyContactPointWarmStarts(fill.pools, mt.points[i], infoGlobal);
}

btScalar btSequentialImpulseConstraintSolverMt::solveGroupCacheFriendlySetup(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifoldPtr, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& infoGlobal,
    btIDebugDraw* debugDrawer)
{
	// Decided before the setup, which converts the contacts (in parallel when batching), on the manifolds
	// that hold points (the island's other manifolds are pairs whose boxes merely overlap).
	int manifoldsWithPoints = 0;
	for (int i = 0; i < numManifolds && manifoldsWithPoints < s_minimumContactManifoldsForBatching; ++i)
		if (manifoldPtr[i]->getNumContacts() > 0) ++manifoldsWithPoints;
	MtSolverScratch& mt = mtScratchOf(*this);
	mt.rowManifolds.resize(0);  // our convertContacts lists them
	mt.plannedManifolds = -1;   // and plans the sweep
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	m_useBatching =
	    manifoldsWithPoints >= s_minimumContactManifoldsForBatching &&
	    !(infoGlobal.m_solverMode & SOLVER_RANDMIZE_ORDER) &&
	    caliber::usesCaliberRowSolvers(m_resolveSingleConstraintRowGeneric, m_resolveSingleConstraintRowLowerLimit);
	scratch.ownContactOrder = m_useBatching;
	const btScalar result = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
	    bodies, numBodies, manifoldPtr, numManifolds, constraints, numConstraints, infoGlobal, debugDrawer);
	scratch.ownContactOrder = false;
	const int numManifoldsWithRows = scratch.manifoldFirstRow.size() - 1;
	m_useBatching = m_useBatching && numManifoldsWithRows > 0;
	btBatchedConstraints& batched = m_batchedContactConstraints;
	if (!m_useBatching)
	{
		batched.m_constraintIndices.resize(0);
		batched.m_batches.resize(0);
		batched.m_phases.resize(0);
		batched.m_phaseGrainSize.resize(0);
		batched.m_phaseOrder.resize(0);
		return result;
	}

	// The sweeps below take the batches' order; the split-impulse pass takes the serial solver's.
	if (infoGlobal.m_splitImpulse)
	{
		caliber::resizeScratch(m_orderTmpConstraintPool, m_tmpSolverContactConstraintPool.size());
		caliber::resizeScratch(mt.byBody, numManifoldsWithRows);  // scratch here: the manifolds in order
		for (int m = 0; m < numManifoldsWithRows; ++m) mt.byBody[m] = m;
		const int chunkManifolds = kOrderBlocksPerTask * kOrderBlockManifolds;
		const int numChunks = (numManifoldsWithRows + chunkManifolds - 1) / chunkManifolds;
		if (mt.pushChunks.size() < numChunks) mt.pushChunks.resize(numChunks);
		WriteContactOrder write;
		write.scratch = &scratch;
		write.order = &m_orderTmpConstraintPool[0];
		write.manifolds = &mt.byBody[0];
		write.contacts = &m_tmpSolverContactConstraintPool;
		write.pushChunks = &mt.pushChunks[0];
		btParallelFor(0, numChunks, 1, write);
		// The push pass's list, in the contact order (the same list its own scan would make).
		scratch.pushRows.resize(0);
		for (int c = 0; c < numChunks; ++c)
		{
			const btAlignedObjectArray<int>& rows = mt.pushChunks[c].rows;
			for (int k = 0; k < rows.size(); ++k) scratch.pushRows.push_back(rows[k]);
		}
		scratch.pushRowsListed = true;
	}

	const btConstraintArray& contacts = m_tmpSolverContactConstraintPool;
	const int numSolverBodies = m_tmpSolverBodyPool.size();
	// A subclass's convertContacts that leaves ours out lists no manifolds: they come from their first rows.
	if (mt.rowManifolds.size() != numManifoldsWithRows)
	{
		caliber::resizeScratch(mt.rowManifolds, numManifoldsWithRows);
		for (int m = 0; m < numManifoldsWithRows; ++m)
		{
			const btSolverConstraint& first = contacts[scratch.manifoldFirstRow[m]];
			MtSolverScratch::RowManifold& manifold = mt.rowManifolds[m];
			manifold.bodyA = first.m_solverBodyIdA;
			manifold.bodyB = first.m_solverBodyIdB;
			manifold.firstPoint = scratch.manifoldFirstRow[m] - scratch.manifoldFirstRow[0];
			manifold.numPoints = scratch.manifoldFirstRow[m + 1] - scratch.manifoldFirstRow[m];
		}
	}
	// The plan, unless our convertContacts made it beside the rows for these manifolds (a subclass's
	// convertContacts may leave ours out, or add rows of its own).
	if (mt.plannedManifolds != numManifoldsWithRows)
	{
		const int numThreads = solveThreads();
		mt.dependentSweep = !caliber::colourSweepBarriers();
		mt.dependenciesListed = mt.dependentSweep && numThreads > 1;
		planColourSweep(mt, &m_tmpSolverBodyPool[0], numSolverBodies, m_fixedBodyId, s_minBatchSize, numThreads,
		                batched);
	}
	writeColourBatchRows(mt, scratch, batched);
	// Each batch's dependencies in the four sweeps (before the fixed entry's copies: each batch has its own).
	if (mt.dependenciesListed) mt.dependencies.listAll();
	if (mt.dependentSweep && mt.itemDone.size() < 2 * batched.m_batches.size())
		mt.itemDone.resize(2 * batched.m_batches.size());

	// Each batch's own copy of the fixed entry (see the file comment), for its contact, friction and
	// rolling rows; the wide sweep's padding lanes use it too (a zero body when there is no fixed entry).
	mt.wide = caliber::wideContactRowsEnabled();
	mt.batchPaddingBody.resize(batched.m_batches.size());
	if (mt.wide && m_fixedBodyId < 0)
	{
		const int firstPadding = m_tmpSolverBodyPool.size();
		btSolverBody zeroBody;
		initSolverBody(&zeroBody, 0, infoGlobal.m_timeStep);
		m_tmpSolverBodyPool.resize(firstPadding + batched.m_batches.size(), zeroBody);
		for (int b = 0; b < batched.m_batches.size(); ++b) mt.batchPaddingBody[b] = firstPadding + b;
	}
	if (m_fixedBodyId >= 0)
	{
		const int firstCopy = m_tmpSolverBodyPool.size();
		const btSolverBody fixedBody = m_tmpSolverBodyPool[m_fixedBodyId];
		m_tmpSolverBodyPool.resize(firstCopy + batched.m_batches.size(), fixedBody);
		for (int b = 0; b < batched.m_batches.size(); ++b) mt.batchPaddingBody[b] = firstCopy + b;
		giveBatchesFixedBodyCopies(batched, &mt.batchesByRun[0], m_fixedBodyId, firstCopy, caliber::frictionRowsPerContact(infoGlobal),
		                           m_tmpSolverContactConstraintPool, m_tmpSolverContactFrictionConstraintPool,
		                           m_tmpSolverContactRollingFrictionConstraintPool);
	}
	groupRollingRows(mt, contacts.size(), m_tmpSolverContactRollingFrictionConstraintPool);

	if (mt.wide)
	{
		mt.wideRows.plan(mt.orderedManifolds, mt.batchManifoldBegin, scratch.manifoldFirstRow,
		                 caliber::frictionRowsPerContact(infoGlobal));
		FillWideRows fill;
		fill.mt = &mt;
		fill.manifoldFirstRow = &scratch.manifoldFirstRow;
		fill.solveCount = scratch.solveCount;
		fill.bodies = &m_tmpSolverBodyPool[0];
		fill.contacts = &m_tmpSolverContactConstraintPool;
		fill.friction = &m_tmpSolverContactFrictionConstraintPool;
		std::atomic<bool> fits(true);
		fill.fits = &fits;
		btParallelFor(0, batched.m_batches.size(), kBatchesPerWideFillTask, fill);
		// Rows the blocks cannot hold: row by row (the same bits).
		mt.wide = fits.load();
	}
	return result;
}

btScalar btSequentialImpulseConstraintSolverMt::solveSingleIteration(int iteration, btCollisionObject** bodies,
                                                                     int numBodies, btPersistentManifold** manifoldPtr,
                                                                     int numManifolds, btTypedConstraint** constraints,
                                                                     int numConstraints,
                                                                     const btContactSolverInfo& infoGlobal,
                                                                     btIDebugDraw* debugDrawer)
{
	if (!m_useBatching)
		return btSequentialImpulseConstraintSolver::solveSingleIteration(iteration, bodies, numBodies, manifoldPtr,
		                                                                 numManifolds, constraints, numConstraints,
		                                                                 infoGlobal, debugDrawer);
	const caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	btSolverBody* solverBodies = &m_tmpSolverBodyPool[0];
	// As the serial solver: every other sweep backwards, joints first (on this thread).
	const bool reverse = ((unsigned(iteration) + scratch.solveCount) & 1u) != 0;
	btScalar residual =
	    caliber::sweepJoints(scratch, solverBodies, m_tmpSolverNonContactConstraintPool, m_tmpConstraintSizesPool,
	                         m_orderNonContactConstraintPool, iteration, reverse);
	if (iteration >= infoGlobal.m_numIterations) return residual;

	const btBatchedConstraints& batched = m_batchedContactConstraints;
	BatchSweep sweep;
	sweep.batched = &batched;
	sweep.bodies = solverBodies;
	sweep.contacts = &m_tmpSolverContactConstraintPool;
	sweep.friction = &m_tmpSolverContactFrictionConstraintPool;
	sweep.rolling = &m_tmpSolverContactRollingFrictionConstraintPool;
	sweep.scratch = &mtScratchOf(*this);
	sweep.batchResidual = 0;
	sweep.frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);
	sweep.reverse = reverse;
	// As in the serial solver, the normal rows of every colour first, so that friction is bounded by this
	// sweep's normal impulses.
	//
	// Each thread takes one run of consecutive batches of a colour (the batches are in body order), so
	// that from colour to colour and sweep to sweep a thread mostly finds its bodies and rows in its own
	// cache: handing out single batches lets them wander between cores, and each core then runs at half
	// speed on cache misses. The runs depend on the thread count, the batches do not; each batch's
	// residual is kept and the sweep's residual summed batch by batch, so the bits do not depend on it.
	const int numThreads = solveThreads();
	const int numPhases = batched.m_phases.size();
	MtSolverScratch& mt = mtScratchOf(*this);
	// (A thread count raised during the solve, after a set-up with one thread: the loop per colour.)
	if (mt.dependentSweep && (mt.dependenciesListed || numThreads == 1))
		residual = sweepWithDependencies(mt, sweep, reverse, numThreads, residual);
	else
		for (int pass = 0; pass < 2; ++pass)
		{
			sweep.pass = pass;
			for (int k = 0; k < numPhases; ++k)
			{
				const btBatchedConstraints::Range& phase =
				    batched.m_phases[batched.m_phaseOrder[reverse ? numPhases - 1 - k : k]];
				const int numBatches = phase.end - phase.begin;
				caliber::resizeScratch(mt.batchResidual, numBatches);
				sweep.firstBatch = phase.begin;
				sweep.batchResidual = &mt.batchResidual[0];
				btParallelFor(0, numBatches, (numBatches + numThreads - 1) / numThreads, sweep);
				for (int b = 0; b < numBatches; ++b) residual += mt.batchResidual[b];
			}
		}
	// After the last sweep of the contacts (the iterations stop at m_numIterations for contacts, or earlier
	// when the residual is small enough), the wide blocks' impulses go to their rows.
	if (mt.wide &&
	    (iteration + 1 >= infoGlobal.m_numIterations || residual <= infoGlobal.m_leastSquaresResidualThreshold))
	{
		StoreWideImpulses store;
		store.wide = &mt.wideRows;
		store.batchesByRun = &mt.batchesByRun;
		store.contacts = &m_tmpSolverContactConstraintPool;
		store.friction = &m_tmpSolverContactFrictionConstraintPool;
		btParallelFor(0, batched.m_batches.size(), kBatchesPerWideFillTask, store);
	}
	return residual;
}

btScalar btSequentialImpulseConstraintSolverMt::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                                              const btContactSolverInfo& infoGlobal)
{
	if (!m_useBatching)
		return btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, infoGlobal);
	// Each contact row into its own manifold point and each solver body into its own body: any order,
	// any thread, the same bits. Joints (feedback, breaking) on this thread.
	struct WriteBack : public btIParallelForBody
	{
		btSequentialImpulseConstraintSolverMt* solver;
		const btContactSolverInfo* info;
		bool contacts;  // else bodies

		void forLoop(int iBegin, int iEnd) const override
		{
			if (contacts)
				solver->writeBackContacts(iBegin, iEnd, *info);
			else
				solver->writeBackBodies(iBegin, iEnd, *info);
		}
	};
	// The contacts batch by batch in the threads' order (batchesByRun), so that a thread writes back the
	// rows it swept, when the batches hold every contact row and there is more than one thread (on one, row
	// by row costs fewer instructions: 2.8 M fewer in stack1000's 60 frames).
	struct WriteBackByBatch : public btIParallelForBody
	{
		btSequentialImpulseConstraintSolverMt* solver;
		const btContactSolverInfo* info;
		const MtSolverScratch* mt;
		const btAlignedObjectArray<int>* manifoldFirstRow;
		caliber::ManifoldOwnerWriter owners;

		void forLoop(int iBegin, int iEnd) const override
		{
			const unsigned int thread = btGetCurrentThreadIndex();
			for (int k = iBegin; k < iEnd; ++k)
			{
				const int b = mt->batchesByRun[k];
				for (int i = mt->batchManifoldBegin[b]; i < mt->batchManifoldBegin[b + 1]; ++i)
				{
					const int m = mt->orderedManifolds[i];
					solver->writeBackContacts((*manifoldFirstRow)[m], (*manifoldFirstRow)[m + 1], *info);
					if (owners)
					{
						const btPersistentManifold* manifold = mt->rowManifoldSource[m];
						owners.note(manifold, manifold->m_index1a, thread);
					}
				}
			}
		}
	};
	WriteBack writeBack;
	writeBack.solver = this;
	writeBack.info = &infoGlobal;
	writeBack.contacts = true;
	const MtSolverScratch& mt = mtScratchOf(*this);
	const btBatchedConstraints& batched = m_batchedContactConstraints;
	const btITaskScheduler* scheduler = btGetTaskScheduler();
	if (scheduler && scheduler->getNumThreads() > 1 &&
	    batched.m_constraintIndices.size() == m_tmpSolverContactConstraintPool.size() &&
	    mt.batchesByRun.size() == batched.m_batches.size() && mt.batchManifoldBegin.size() == batched.m_batches.size() + 1)
	{
		WriteBackByBatch byBatch;
		byBatch.solver = this;
		byBatch.info = &infoGlobal;
		byBatch.mt = &mt;
		byBatch.manifoldFirstRow = &caliber::solverScratchOf(*this).manifoldFirstRow;
		// The next narrowphase gives each manifold's pair to the thread that wrote it here (its sweep's).
		if (mt.rowManifoldSource.size() == mt.rowManifolds.size())
			byBatch.owners = caliber::manifoldOwnerWriter(caliber::scopedSolveDispatcher());
		btParallelFor(0, batched.m_batches.size(), kBatchesPerWideFillTask, byBatch);
	}
	else
		btParallelFor(0, m_tmpSolverContactConstraintPool.size(), kRowsPerWriteBackTask, writeBack);
	writeBackJoints(0, caliber::solverScratchOf(*this).joints.size(), infoGlobal);
	// The bodies by run when the plan listed them (see MtSolverScratch::bodiesByRun), so that a thread
	// writes back the bodies it swept; the entries made after the plan (the batches' copies of the fixed
	// entry, the wide sweep's padding bodies) belong to no rigid body and go on this thread.
	struct WriteBackBySlice : public btIParallelForBody
	{
		btSequentialImpulseConstraintSolverMt* solver;
		const btContactSolverInfo* info;
		BodySlices slices;

		void forLoop(int iBegin, int iEnd) const override
		{
			for (int c = iBegin; c < iEnd; ++c)
			{
				int begin, end;
				slices.slice(c, begin, end);
				// Consecutive bodies in one call.
				for (int k = begin, span; k < end; k += span)
				{
					span = 1;
					while (k + span < end && slices.bodies[k + span] == slices.bodies[k] + span) ++span;
					solver->writeBackBodies(slices.bodies[k], slices.bodies[k] + span, *info);
				}
			}
		}
	};
	const int listedBodies = mt.bodiesByRun.size();
	WriteBackBySlice bySlice;
	bySlice.slices = BodySlices::of(mt, btMin(listedBodies, m_tmpSolverBodyPool.size()), kBodiesPerWriteBackTask);
	if (bySlice.slices.runs)
	{
		bySlice.solver = this;
		bySlice.info = &infoGlobal;
		btParallelFor(0, bySlice.slices.count(), 1, bySlice);
		writeBackBodies(listedBodies, m_tmpSolverBodyPool.size(), infoGlobal);
	}
	else
	{
		writeBack.contacts = false;
		btParallelFor(0, m_tmpSolverBodyPool.size(), kBodiesPerWriteBackTask, writeBack);
	}
	return btScalar(0);
}
