// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btSliderConstraint.h"

#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "LinearMath/btWarningHook.h"

// The rows, with R the reference frame (A's or B's), M the other one, a = R's X axis, p and q R's Y and Z
// made orthogonal to a, and s the slide position (M's origin minus R's, along a, signed as in the header):
//   two angular rows   (wA - wB) . p, q    keep the X axes parallel;
//   two linear rows    along p, q          keep M's origin on R's X axis;
//   then, when locked, the turn about a and the slide along a; then the limit and motor rows.
// Every linear row measures both bodies at M's origin. That is the exact time derivative of that origin's
// offset from the line R carries (the line turns with R's body, which moves that body's arm from R's origin
// to M's), and it makes the two bodies' impulses act at one point, so the joint applies no torque couple.
// The linear rows along the axis use direction +a when R is A and -a when R is B, so that each of them
// reads -ds/dt; the angular rows about a read -d(angle)/dt. Limit rows are present whenever a range is
// set and look ahead: they let the body reach the limit in this step and no further (gap / h), and
// push back at ERP once it is past, so a slider stops on its limit instead of sinking into it.

namespace
{
// Finite, and its axes span space: each has length, and together they are not close to coplanar (the
// determinant is at least 1 % of the product of the lengths, which is what orthogonal axes give).
bool isUsableFrame(const btTransform& frame)
{
	if (!caliber::isFinite(frame.getOrigin())) return false;
	const btMatrix3x3& basis = frame.getBasis();
	btScalar lengths = 1;
	for (int i = 0; i < 3; ++i)
	{
		const btVector3 column = basis.getColumn(i);
		if (!caliber::isFinite(column)) return false;
		const btScalar length = column.length();
		if (!(length > btScalar(1e-6))) return false;
		lengths *= length;
	}
	return btFabs(basis.determinant()) > btScalar(0.01) * lengths;
}

// Checks both frames; reports and disables the joint when one is non-finite or degenerate
// (assertOnFailure: the caller has just handed the frame in, a programming error).
bool framesUsable(btSliderConstraint& joint, bool assertOnFailure)
{
	if (isUsableFrame(joint.getFrameOffsetA()) && isUsableFrame(joint.getFrameOffsetB())) return true;
	btAssert(!assertOnFailure && "btSliderConstraint: a frame is not finite or its axes are degenerate");
	(void)assertOnFailure;
	btReportWarning("Caliber: btSliderConstraint: a frame is not finite or its axes are degenerate; it is disabled\n",
	                0);
	joint.setEnabled(false);
	return false;
}

btVector3 column(const btTransform& frame, int i) { return frame.getBasis().getColumn(i).normalized(); }

// The row's ERP: the softness scales the world's ERP until setParam makes it the ERP itself.
btScalar rowErp(int flags, int flag, btScalar softness, btScalar worldErp)
{
	return (flags & flag) ? softness : softness * worldErp;
}

// How much of the approach speed a limit gives back (Bullet's |1 - damping|, kept within [0, 1]).
btScalar bounceOf(btScalar damping) { return btMax(btScalar(0), btMin(btScalar(1), btScalar(1) - damping)); }

// Which rows the joint has; it depends on the parameters only, so getInfo1 and getInfo2 always agree.
struct RowLayout
{
	bool angLock, linLock, linLimit, linMotor, angLimit, angMotor;
	int equalityRows, rows;

	RowLayout(btScalar lowLin, btScalar upLin, bool linPowered, btScalar lowAng, btScalar upAng, bool angPowered)
	{
		linLock = lowLin == upLin;
		linLimit = lowLin < upLin;
		linMotor = linPowered && !linLock;
		angLock = lowAng == upAng;
		angLimit = lowAng < upAng;
		angMotor = angPowered && !angLock;
		equalityRows = 4 + int(angLock) + int(linLock);
		rows = equalityRows + int(linLimit) + int(linMotor) + int(angLimit) + int(angMotor);
	}
};

// A one-sided limit row on a coordinate x whose rate is -J v (the row's J v reads -dx/dt): it keeps x
// above lower (nearLower) or below upper, looking ahead one step; bounce gives back that fraction of the
// approach speed.
void writeLimitRow(caliber::JointRow& row, bool nearLower, btScalar x, btScalar lower, btScalar upper, btScalar rate,
                   btScalar fps, btScalar erp, btScalar bounce)
{
	if (nearLower)
	{
		// dx/dt >= -gap / h before the limit, erp * |gap| / h past it: J v <= target, impulse <= 0.
		const btScalar gap = x - lower;
		btScalar target = gap >= 0 ? gap * fps : erp * fps * gap;
		const btScalar approach = -rate;
		if (bounce > 0 && approach > 0 && approach >= gap * fps) target = btMin(target, -bounce * approach);
		row.error() = target;
		row.lower() = -SIMD_INFINITY;
		row.upper() = 0;
	}
	else
	{
		const btScalar gap = upper - x;
		btScalar target = gap >= 0 ? -gap * fps : -erp * fps * gap;
		const btScalar approach = rate;
		if (bounce > 0 && approach > 0 && approach >= gap * fps) target = btMax(target, bounce * approach);
		row.error() = target;
		row.lower() = 0;
		row.upper() = SIMD_INFINITY;
	}
}

// The limit and motor rows come after the equality block, which the solver solves exactly; the rows after
// it are solved one at a time. When a body's centre of mass lies off the axis, a turn about the axis moves
// the point the linear rows hold, so those rows and the limit or motor rows are strongly coupled and
// alternating between them converges slowly (0.96 per iteration for a ball 0.3 m off the axis). Taking
// from each later row its mass-weighted projection onto the block rows, J' = J - c J_block with
// c = K_block^-1 J_block M^-1 J^T, removes the coupling: the row's impulse no longer disturbs the block,
// so one pass settles both. Where the block rows hold (J_block v = their targets) J' v >= t' is the same
// condition as J v >= t, and the impulses span the same joint forces with the same multiplier, so bounds,
// momentum and the answer are unchanged; only the convergence is.
class BlockDecoupler
{
public:
	BlockDecoupler(const btRigidBody& a, const btRigidBody& b)
	{
		setBody(a, m_invMassA, m_invInertiaA);
		setBody(b, m_invMassB, m_invInertiaB);
	}

	// Rows [0, blockRows) are the block; rows [blockRows, rows) are made independent of it.
	static const int kMaxRows = 8;

	void apply(btTypedConstraint::btConstraintInfo2& info, int blockRows, int rows) const
	{
		if (!info.m_J2linearAxis || blockRows <= 0 || rows <= blockRows || rows > kMaxRows) return;
		btVector3 j[kMaxRows][4];
		for (int r = 0; r < rows; ++r)
		{
			btScalar* fields[4] = {info.m_J1linearAxis, info.m_J1angularAxis, info.m_J2linearAxis,
			                       info.m_J2angularAxis};
			for (int f = 0; f < 4; ++f)
			{
				const btScalar* p = fields[f] + r * info.rowskip;
				j[r][f].setValue(p[0], p[1], p[2]);
			}
		}
		// K = J M^-1 J^T over the block, and its products with each later row.
		btScalar k[kMaxRows][kMaxRows + 1];
		for (int later = blockRows; later < rows; ++later)
		{
			for (int r = 0; r < blockRows; ++r)
			{
				for (int c = 0; c < blockRows; ++c) k[r][c] = weighted(j[r], j[c]);
				k[r][blockRows] = weighted(j[r], j[later]);
			}
			btScalar c[kMaxRows];
			if (!solve(k, blockRows, c)) return;  // singular: leave the rows as they are
			btScalar* fields[4] = {info.m_J1linearAxis, info.m_J1angularAxis, info.m_J2linearAxis,
			                       info.m_J2angularAxis};
			btScalar& error = info.m_constraintError[later * info.rowskip];
			for (int r = 0; r < blockRows; ++r)
			{
				for (int f = 0; f < 4; ++f) j[later][f] -= j[r][f] * c[r];
				error -= c[r] * info.m_constraintError[r * info.rowskip];
			}
			for (int f = 0; f < 4; ++f)
			{
				btScalar* p = fields[f] + later * info.rowskip;
				p[0] = j[later][f].x();
				p[1] = j[later][f].y();
				p[2] = j[later][f].z();
			}
		}
	}

private:
	// What the solver uses: the inverse mass times the linear factor, and the inverse world inertia
	// between the angular factors; nothing for static and kinematic bodies.
	static void setBody(const btRigidBody& body, btVector3& invMass, btMatrix3x3& invInertia)
	{
		invMass = body.getLinearFactor() * body.getInvMass();
		invInertia.setValue(0, 0, 0, 0, 0, 0, 0, 0, 0);
		if (body.isStaticOrKinematicObject()) return;
		const btVector3& f = body.getAngularFactor();
		const btMatrix3x3& i = body.getInvInertiaTensorWorld();
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) invInertia[r][c] = f[r] * i[r][c] * f[c];
	}

	btScalar weighted(const btVector3* x, const btVector3* y) const
	{
		return x[0].dot(m_invMassA * y[0]) + x[1].dot(m_invInertiaA * y[1]) + x[2].dot(m_invMassB * y[2]) +
		       x[3].dot(m_invInertiaB * y[3]);
	}

	// Gaussian elimination with partial pivoting on the n x (n + 1) system k; false if it is singular
	// (relative to its largest diagonal entry).
	static bool solve(btScalar (*k)[kMaxRows + 1], int n, btScalar* x)
	{
		btScalar largest = 0;
		for (int i = 0; i < n; ++i) largest = btMax(largest, btFabs(k[i][i]));
		if (!(largest > 0)) return false;
		const btScalar tiny = largest * btScalar(1e-5);
		for (int c = 0; c < n; ++c)
		{
			int pivot = c;
			for (int r = c + 1; r < n; ++r)
				if (btFabs(k[r][c]) > btFabs(k[pivot][c])) pivot = r;
			if (!(btFabs(k[pivot][c]) > tiny)) return false;
			if (pivot != c)
				for (int m = 0; m <= n; ++m) btSwap(k[c][m], k[pivot][m]);
			for (int r = c + 1; r < n; ++r)
			{
				const btScalar f = k[r][c] / k[c][c];
				for (int m = c; m <= n; ++m) k[r][m] -= f * k[c][m];
			}
		}
		for (int r = n - 1; r >= 0; --r)
		{
			btScalar sum = k[r][n];
			for (int m = r + 1; m < n; ++m) sum -= k[r][m] * x[m];
			x[r] = sum / k[r][r];
		}
		return true;
	}

	btVector3 m_invMassA, m_invMassB;
	btMatrix3x3 m_invInertiaA, m_invInertiaB;
};

// The two directions across the slider axis that rows 0-3 act along. They turn with the reference frame,
// so a row keeps its meaning (and its warm-start impulse) from one step to the next.
struct CrossDirections
{
	btVector3 dir[2];
	CrossDirections(const btTransform& reference, const btVector3& axis)
	{
		const btVector3 referenceY = column(reference, 1);
		dir[0] = (referenceY - axis * axis.dot(referenceY)).normalized();
		dir[1] = axis.cross(dir[0]);
	}
};

// Rows 0-1: the X axes parallel. The error is the rotation vector taking A's X axis onto B's (angle times
// unit axis, exact at any angle); the rows turn B back by erp of it per step.
void writeAxisAlignmentRows(btTypedConstraint::btConstraintInfo2& info, const btTransform& frameA,
                            const btTransform& frameB, const CrossDirections& cross, btScalar erp, const btScalar* cfm)
{
	const btVector3 xA = column(frameA, 0), xB = column(frameB, 0);
	const btVector3 sinAxis = xA.cross(xB);
	const btScalar sinAngle = sinAxis.length();
	const btVector3 swing = sinAngle > btScalar(1e-7) ? sinAxis * (btAtan2(sinAngle, xA.dot(xB)) / sinAngle) : sinAxis;
	for (int i = 0; i < 2; ++i)
	{
		caliber::JointRow row(info, i);
		row.setAngular(cross.dir[i]);
		row.error() = info.fps * erp * swing.dot(cross.dir[i]);
		if (cfm) row.cfm() = *cfm;
	}
}

// Rows 2-3: the other frame's origin on the reference axis (offset is pivot B minus pivot A), both bodies
// measured at that origin (arms from their centres).
void writeOnAxisRows(btTypedConstraint::btConstraintInfo2& info, const CrossDirections& cross, const btVector3& armA,
                     const btVector3& armB, const btVector3& offset, btScalar erp, const btScalar* cfm)
{
	for (int i = 0; i < 2; ++i)
	{
		caliber::JointRow row(info, 2 + i);
		row.setLinear(cross.dir[i], armA, armB);
		row.error() = info.fps * erp * offset.dot(cross.dir[i]);
		if (cfm) row.cfm() = *cfm;
	}
}

// A motor row's impulse bounds: the motor's force over one step (a negative force counts as none).
void boundMotorRow(caliber::JointRow& row, btScalar maxForce, btScalar fps)
{
	const btScalar bound = btMax(btScalar(0), maxForce) / fps;
	row.lower() = -bound;
	row.upper() = bound;
}
}  // namespace

void btSliderConstraint::initParams()
{
	// Limits start inverted (lower > upper: the linear axis is free) and the angular range is zero.
	m_lowerLinLimit = btScalar(1);
	m_upperLinLimit = btScalar(-1);
	m_lowerAngLimit = btScalar(0);
	m_upperAngLimit = btScalar(0);

	// The six groups of rows (along the axis, across it, at a limit; each linear and angular) share their
	// defaults, except that the rows along the free axis start undamped.
	struct RowSettings
	{
		btScalar btSliderConstraint::*softness;
		btScalar btSliderConstraint::*restitution;
		btScalar btSliderConstraint::*damping;
		btScalar btSliderConstraint::*cfm;
		bool alongFreeAxis;
	};
	static const RowSettings kRowGroups[] = {
	    {&btSliderConstraint::m_softnessDirLin, &btSliderConstraint::m_restitutionDirLin,
	     &btSliderConstraint::m_dampingDirLin, &btSliderConstraint::m_cfmDirLin, true},
	    {&btSliderConstraint::m_softnessDirAng, &btSliderConstraint::m_restitutionDirAng,
	     &btSliderConstraint::m_dampingDirAng, &btSliderConstraint::m_cfmDirAng, true},
	    {&btSliderConstraint::m_softnessOrthoLin, &btSliderConstraint::m_restitutionOrthoLin,
	     &btSliderConstraint::m_dampingOrthoLin, &btSliderConstraint::m_cfmOrthoLin, false},
	    {&btSliderConstraint::m_softnessOrthoAng, &btSliderConstraint::m_restitutionOrthoAng,
	     &btSliderConstraint::m_dampingOrthoAng, &btSliderConstraint::m_cfmOrthoAng, false},
	    {&btSliderConstraint::m_softnessLimLin, &btSliderConstraint::m_restitutionLimLin,
	     &btSliderConstraint::m_dampingLimLin, &btSliderConstraint::m_cfmLimLin, false},
	    {&btSliderConstraint::m_softnessLimAng, &btSliderConstraint::m_restitutionLimAng,
	     &btSliderConstraint::m_dampingLimAng, &btSliderConstraint::m_cfmLimAng, false},
	};
	for (const RowSettings& group : kRowGroups)
	{
		this->*group.softness = SLIDER_CONSTRAINT_DEF_SOFTNESS;
		this->*group.restitution = SLIDER_CONSTRAINT_DEF_RESTITUTION;
		this->*group.damping = group.alongFreeAxis ? btScalar(0) : btScalar(SLIDER_CONSTRAINT_DEF_DAMPING);
		this->*group.cfm = SLIDER_CONSTRAINT_DEF_CFM;
	}

	m_solveLinLim = false;
	m_solveAngLim = false;
	m_flags = 0;

	m_poweredLinMotor = false;
	m_targetLinMotorVelocity = btScalar(0);
	m_maxLinMotorForce = btScalar(0);
	m_poweredAngMotor = false;
	m_targetAngMotorVelocity = btScalar(0);
	m_maxAngMotorForce = btScalar(0);

	m_calculatedTransformA.setIdentity();
	m_calculatedTransformB.setIdentity();
	m_sliderAxis.setValue(1, 0, 0);
	m_realPivotAInW.setZero();
	m_realPivotBInW.setZero();
	m_linPos = m_angPos = m_linDepth = m_angDepth = btScalar(0);

	if (framesUsable(*this, true))
	{
		calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
		testLinLimits();
		testAngLimits();
	}
}

btSliderConstraint::btSliderConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& frameInA,
                                       const btTransform& frameInB, bool useLinearReferenceFrameA)
    : btTypedConstraint(SLIDER_CONSTRAINT_TYPE, rbA, rbB),
      m_useSolveConstraintObsolete(false),
      m_useOffsetForConstraintFrame(true),
      m_frameInA(frameInA),
      m_frameInB(frameInB),
      m_useLinearReferenceFrameA(useLinearReferenceFrameA)
{
	initParams();
}

btSliderConstraint::btSliderConstraint(btRigidBody& rbB, const btTransform& frameInB, bool useLinearReferenceFrameA)
    : btTypedConstraint(SLIDER_CONSTRAINT_TYPE, getFixedBody(), rbB),
      m_useSolveConstraintObsolete(false),
      m_useOffsetForConstraintFrame(true),
      m_frameInA(rbB.getCenterOfMassTransform() * frameInB),
      m_frameInB(frameInB),
      m_useLinearReferenceFrameA(useLinearReferenceFrameA)
{
	initParams();
}

void btSliderConstraint::setFrames(const btTransform& frameA, const btTransform& frameB)
{
	m_frameInA = frameA;
	m_frameInB = frameB;
	if (!framesUsable(*this, true)) return;
	calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
	testLinLimits();
	testAngLimits();
}

void btSliderConstraint::calculateTransforms(const btTransform& transA, const btTransform& transB)
{
	m_calculatedTransformA = transA * m_frameInA;
	m_calculatedTransformB = transB * m_frameInB;
	m_realPivotAInW = m_calculatedTransformA.getOrigin();
	m_realPivotBInW = m_calculatedTransformB.getOrigin();
	const btTransform& reference = m_useLinearReferenceFrameA ? m_calculatedTransformA : m_calculatedTransformB;
	m_sliderAxis = column(reference, 0);
	const btScalar sign = m_useLinearReferenceFrameA ? btScalar(1) : btScalar(-1);
	m_linPos = sign * (m_realPivotBInW - m_realPivotAInW).dot(m_sliderAxis);
	// B's Y axis seen in A's Y-Z plane.
	const btVector3 yB = column(m_calculatedTransformB, 1);
	m_angPos = btAtan2(yB.dot(column(m_calculatedTransformA, 2)), yB.dot(column(m_calculatedTransformA, 1)));
}

void btSliderConstraint::testLinLimits()
{
	m_solveLinLim = false;
	m_linDepth = btScalar(0);
	if (!(m_lowerLinLimit <= m_upperLinLimit)) return;
	if (m_linPos > m_upperLinLimit)
	{
		m_linDepth = m_linPos - m_upperLinLimit;
		m_solveLinLim = true;
	}
	else if (m_linPos < m_lowerLinLimit)
	{
		m_linDepth = m_linPos - m_lowerLinLimit;
		m_solveLinLim = true;
	}
}

void btSliderConstraint::testAngLimits()
{
	m_solveAngLim = false;
	m_angDepth = btScalar(0);
	if (!(m_lowerAngLimit <= m_upperAngLimit)) return;
	m_angPos = btAdjustAngleToLimits(m_angPos, m_lowerAngLimit, m_upperAngLimit);
	if (m_angPos > m_upperAngLimit)
	{
		m_angDepth = m_angPos - m_upperAngLimit;
		m_solveAngLim = true;
	}
	else if (m_angPos < m_lowerAngLimit)
	{
		m_angDepth = m_angPos - m_lowerAngLimit;
		m_solveAngLim = true;
	}
}

btVector3 btSliderConstraint::getAncorInA()
{
	const btVector3 middle = m_realPivotAInW + m_sliderAxis * ((m_lowerLinLimit + m_upperLinLimit) * btScalar(0.5));
	return m_rbA.getCenterOfMassTransform().invXform(middle);
}

btVector3 btSliderConstraint::getAncorInB() { return m_frameInB.getOrigin(); }

void btSliderConstraint::getInfo1(btConstraintInfo1* info) { getInfo1NonVirtual(info); }

void btSliderConstraint::getInfo1NonVirtual(btConstraintInfo1* info)
{
	info->m_numConstraintRows = 0;
	info->nub = 0;
	// The frames are public (getFrameOffsetA returns a reference), so they are checked every step.
	if (!framesUsable(*this, false)) return;
	calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
	testLinLimits();
	testAngLimits();
	const RowLayout layout(m_lowerLinLimit, m_upperLinLimit, m_poweredLinMotor, m_lowerAngLimit, m_upperAngLimit,
	                       m_poweredAngMotor);
	info->m_numConstraintRows = layout.rows;
	info->nub = layout.equalityRows;
}

void btSliderConstraint::getInfo2(btConstraintInfo2* info)
{
	getInfo2NonVirtual(info, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(),
	                   m_rbA.getLinearVelocity(), m_rbB.getLinearVelocity(), m_rbA.getInvMass(), m_rbB.getInvMass());
}

void btSliderConstraint::getInfo2NonVirtual(btConstraintInfo2* info, const btTransform& transA,
                                            const btTransform& transB, const btVector3& linVelA,
                                            const btVector3& linVelB, btScalar rbAinvMass, btScalar rbBinvMass)
{
	(void)rbAinvMass;
	(void)rbBinvMass;
	calculateTransforms(transA, transB);
	testLinLimits();
	testAngLimits();
	const RowLayout layout(m_lowerLinLimit, m_upperLinLimit, m_poweredLinMotor, m_lowerAngLimit, m_upperAngLimit,
	                       m_poweredAngMotor);

	const btTransform& reference = m_useLinearReferenceFrameA ? m_calculatedTransformA : m_calculatedTransformB;
	const btVector3& axis = m_sliderAxis;
	const CrossDirections cross(reference, axis);
	const btScalar fps = info->fps;
	writeAxisAlignmentRows(*info, m_calculatedTransformA, m_calculatedTransformB, cross,
	                       rowErp(m_flags, BT_SLIDER_FLAGS_ERP_ORTANG, m_softnessOrthoAng, info->erp),
	                       (m_flags & BT_SLIDER_FLAGS_CFM_ORTANG) ? &m_cfmOrthoAng : 0);
	const btVector3 point = m_useLinearReferenceFrameA ? m_realPivotBInW : m_realPivotAInW;
	const btVector3 armA = point - transA.getOrigin();
	const btVector3 armB = point - transB.getOrigin();
	writeOnAxisRows(*info, cross, armA, armB, m_realPivotBInW - m_realPivotAInW,
	                rowErp(m_flags, BT_SLIDER_FLAGS_ERP_ORTLIN, m_softnessOrthoLin, info->erp),
	                (m_flags & BT_SLIDER_FLAGS_CFM_ORTLIN) ? &m_cfmOrthoLin : 0);

	// The slide direction whose row reads -ds/dt, and the rates the limits' bounce needs.
	const btVector3 slide = m_useLinearReferenceFrameA ? axis : -axis;
	const btVector3 angVelA = m_rbA.getAngularVelocity(), angVelB = m_rbB.getAngularVelocity();
	const btScalar linRate = -slide.dot(linVelA + angVelA.cross(armA) - linVelB - angVelB.cross(armB));
	const btScalar angRate = -axis.dot(angVelA - angVelB);
	const btScalar erpLimLin = rowErp(m_flags, BT_SLIDER_FLAGS_ERP_LIMLIN, m_softnessLimLin, info->erp);
	const btScalar erpLimAng = rowErp(m_flags, BT_SLIDER_FLAGS_ERP_LIMANG, m_softnessLimAng, info->erp);

	int next = 4;
	if (layout.angLock)
	{
		caliber::JointRow row(*info, next++);
		row.setAngular(axis);
		row.error() = fps * erpLimAng * btNormalizeAngle(m_angPos - m_lowerAngLimit);
		if (m_flags & BT_SLIDER_FLAGS_CFM_LIMANG) row.cfm() = m_cfmLimAng;
	}
	if (layout.linLock)
	{
		caliber::JointRow row(*info, next++);
		row.setLinear(slide, armA, armB);
		row.error() = fps * erpLimLin * (m_linPos - m_lowerLinLimit);
		if (m_flags & BT_SLIDER_FLAGS_CFM_LIMLIN) row.cfm() = m_cfmLimLin;
	}
	if (layout.linLimit)
	{
		caliber::JointRow row(*info, next++);
		row.setLinear(slide, armA, armB);
		const bool nearLower = m_linPos < btScalar(0.5) * (m_lowerLinLimit + m_upperLinLimit);
		writeLimitRow(row, nearLower, m_linPos, m_lowerLinLimit, m_upperLinLimit, linRate, fps, erpLimLin,
		              bounceOf(m_dampingLimLin));
		if (m_flags & BT_SLIDER_FLAGS_CFM_LIMLIN) row.cfm() = m_cfmLimLin;
	}
	if (layout.linMotor)
	{
		caliber::JointRow row(*info, next++);
		row.setLinear(slide, armA, armB);
		const btScalar erpDirLin = rowErp(m_flags, BT_SLIDER_FLAGS_ERP_DIRLIN, m_softnessDirLin, info->erp);
		const btScalar factor =
		    getMotorFactor(m_linPos, m_lowerLinLimit, m_upperLinLimit, m_targetLinMotorVelocity, fps * erpDirLin);
		row.error() = -factor * m_targetLinMotorVelocity;
		boundMotorRow(row, m_maxLinMotorForce, fps);
		if (m_flags & BT_SLIDER_FLAGS_CFM_DIRLIN) row.cfm() = m_cfmDirLin;
	}
	if (layout.angLimit)
	{
		caliber::JointRow row(*info, next++);
		row.setAngular(axis);
		const bool nearLower = m_angPos < btScalar(0.5) * (m_lowerAngLimit + m_upperAngLimit);
		writeLimitRow(row, nearLower, m_angPos, m_lowerAngLimit, m_upperAngLimit, angRate, fps, erpLimAng,
		              bounceOf(m_dampingLimAng));
		if (m_flags & BT_SLIDER_FLAGS_CFM_LIMANG) row.cfm() = m_cfmLimAng;
	}
	if (layout.angMotor)
	{
		caliber::JointRow row(*info, next++);
		row.setAngular(axis);
		// The motor turns the angle at minus its target (Bullet's convention), so that is the rate the
		// fade-out near a limit is judged by.
		const btScalar erpDirAng = rowErp(m_flags, BT_SLIDER_FLAGS_ERP_DIRANG, m_softnessDirAng, info->erp);
		const btScalar factor =
		    getMotorFactor(m_angPos, m_lowerAngLimit, m_upperAngLimit, -m_targetAngMotorVelocity, fps * erpDirAng);
		row.error() = factor * m_targetAngMotorVelocity;
		boundMotorRow(row, m_maxAngMotorForce, fps);
		if (m_flags & BT_SLIDER_FLAGS_CFM_DIRANG) row.cfm() = m_cfmDirAng;
	}
	btAssert(next == layout.rows);

	// The block the solver will solve exactly: the leading equality rows, up to the first one made soft.
	int blockRows = 0;
	while (blockRows < layout.equalityRows && info->cfm[blockRows * info->rowskip] == btScalar(0)) ++blockRows;
	BlockDecoupler(m_rbA, m_rbB).apply(*info, blockRows, layout.rows);
}

namespace
{
// The member and flag that setParam / getParam address for (num, axis); false if there is none. The
// protected members are named through a class derived from the slider (it is never built).
struct SliderParamSlots : btSliderConstraint
{
	static bool find(int num, int axis, btScalar btSliderConstraint::*& member, int& flag)
	{
		if (axis < -1 || axis > 5) return false;
		const bool across = axis == 1 || axis == 2 || axis == 4 || axis == 5;
		const bool angular = axis >= 3;
		switch (num)
		{
			case BT_CONSTRAINT_STOP_ERP:
				if (across)
				{
					member = angular ? &SliderParamSlots::m_softnessOrthoAng : &SliderParamSlots::m_softnessOrthoLin;
					flag = angular ? BT_SLIDER_FLAGS_ERP_ORTANG : BT_SLIDER_FLAGS_ERP_ORTLIN;
				}
				else
				{
					member = angular ? &SliderParamSlots::m_softnessLimAng : &SliderParamSlots::m_softnessLimLin;
					flag = angular ? BT_SLIDER_FLAGS_ERP_LIMANG : BT_SLIDER_FLAGS_ERP_LIMLIN;
				}
				return true;
			case BT_CONSTRAINT_ERP:
				if (across)
				{
					member = angular ? &SliderParamSlots::m_softnessOrthoAng : &SliderParamSlots::m_softnessOrthoLin;
					flag = angular ? BT_SLIDER_FLAGS_ERP_ORTANG : BT_SLIDER_FLAGS_ERP_ORTLIN;
				}
				else
				{
					member = angular ? &SliderParamSlots::m_softnessDirAng : &SliderParamSlots::m_softnessDirLin;
					flag = angular ? BT_SLIDER_FLAGS_ERP_DIRANG : BT_SLIDER_FLAGS_ERP_DIRLIN;
				}
				return true;
			case BT_CONSTRAINT_STOP_CFM:
				if (across)
				{
					member = angular ? &SliderParamSlots::m_cfmOrthoAng : &SliderParamSlots::m_cfmOrthoLin;
					flag = angular ? BT_SLIDER_FLAGS_CFM_ORTANG : BT_SLIDER_FLAGS_CFM_ORTLIN;
				}
				else
				{
					member = angular ? &SliderParamSlots::m_cfmLimAng : &SliderParamSlots::m_cfmLimLin;
					flag = angular ? BT_SLIDER_FLAGS_CFM_LIMANG : BT_SLIDER_FLAGS_CFM_LIMLIN;
				}
				return true;
			case BT_CONSTRAINT_CFM:
				if (across)
				{
					member = angular ? &SliderParamSlots::m_cfmOrthoAng : &SliderParamSlots::m_cfmOrthoLin;
					flag = angular ? BT_SLIDER_FLAGS_CFM_ORTANG : BT_SLIDER_FLAGS_CFM_ORTLIN;
				}
				else
				{
					member = angular ? &SliderParamSlots::m_cfmDirAng : &SliderParamSlots::m_cfmDirLin;
					flag = angular ? BT_SLIDER_FLAGS_CFM_DIRANG : BT_SLIDER_FLAGS_CFM_DIRLIN;
				}
				return true;
			default:
				return false;
		}
	}
};
}  // namespace

void btSliderConstraint::setParam(int num, btScalar value, int axis)
{
	btScalar btSliderConstraint::*member = 0;
	int flag = 0;
	const bool known = SliderParamSlots::find(num, axis, member, flag);
	btAssertConstrParams(known);
	if (!known) return;
	this->*member = value;
	m_flags |= flag;
}

btScalar btSliderConstraint::getParam(int num, int axis) const
{
	btScalar btSliderConstraint::*member = 0;
	int flag = 0;
	const bool known = SliderParamSlots::find(num, axis, member, flag);
	btAssertConstrParams(known);
	if (!known) return SIMD_INFINITY;
	btAssertConstrParams(m_flags & flag);
	return this->*member;
}
