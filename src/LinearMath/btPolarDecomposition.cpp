// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btPolarDecomposition.h"

// A step change of 1e-4 leaves an error of about 1e-8 after the next step, below float rounding; the
// extra unscaled step (see the header) covers double.
const btScalar btPolarDecomposition::DEFAULT_TOLERANCE = btScalar(1.0e-4);
const unsigned int btPolarDecomposition::DEFAULT_MAX_ITERATIONS = 16;

namespace
{
btScalar frobeniusNorm2(const btMatrix3x3& m) { return m[0].length2() + m[1].length2() + m[2].length2(); }

// (m + m^T) / 2.
btMatrix3x3 symmetricPart(const btMatrix3x3& m) { return (m + m.transpose()) * btScalar(0.5); }

// The orthogonal factor of a (Frobenius norm 1) from the eigenvectors of a^T a: with a^T a = V D V^T
// and v_i the columns of V by decreasing eigenvalue, u maps v_i to the unit vector along a v_i. The
// third image, and the second when a has rank 1, is completed by cross products, so u is a rotation
// and a v_i = sigma_i u v_i holds for every non-zero singular value.
btMatrix3x3 orthogonalFactorOfSingular(const btMatrix3x3& a)
{
	btMatrix3x3 gram = a.transposeTimes(a);
	btMatrix3x3 eigenvectors;
	eigenvectors.setIdentity();
	gram.diagonalize(eigenvectors, SIMD_EPSILON, 64);

	int order[3] = {0, 1, 2};
	for (int i = 0; i < 2; ++i)
		for (int j = i + 1; j < 3; ++j)
			if (gram[order[j]][order[j]] > gram[order[i]][order[i]])
			{
				const int swapped = order[i];
				order[i] = order[j];
				order[j] = swapped;
			}
	btVector3 v[3];
	for (int i = 0; i < 3; ++i) v[i] = eigenvectors.getColumn(order[i]);
	if (btTriple(v[0], v[1], v[2]) < btScalar(0)) v[2] = -v[2];

	// a has norm 1, so singular values below a few rounding units are noise.
	const btScalar rankTolerance = btScalar(16) * SIMD_EPSILON;
	btVector3 image[3];
	image[0] = a * v[0];
	const btScalar length0 = image[0].length();
	if (!(length0 > rankTolerance)) return btMatrix3x3::getIdentity();
	image[0] /= length0;
	image[1] = a * v[1];
	image[1] -= image[0] * image[0].dot(image[1]);
	const btScalar length1 = image[1].length();
	if (length1 > rankTolerance)
		image[1] /= length1;
	else
		btPlaneSpace1(image[0], image[1], image[2]);
	image[2] = image[0].cross(image[1]);

	// u = sum_i image_i v_i^T.
	btMatrix3x3 u;
	u.setZero();
	for (int r = 0; r < 3; ++r)
		for (int c = 0; c < 3; ++c) u[r][c] = image[0][r] * v[0][c] + image[1][r] * v[1][c] + image[2][r] * v[2][c];
	return u;
}
}  // namespace

btPolarDecomposition::btPolarDecomposition(btScalar tolerance, unsigned int maxIterations)
    : m_tolerance(tolerance), m_maxIterations(maxIterations)
{
}

unsigned int btPolarDecomposition::maxIterations() const { return m_maxIterations; }

unsigned int btPolarDecomposition::decompose(const btMatrix3x3& a, btMatrix3x3& u, btMatrix3x3& h) const
{
	btScalar largest = 0;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) largest = btMax(largest, btFabs(a[i][j]));
	if (!caliber::isFinite(a) || !(largest > btScalar(0)))
	{
		u.setIdentity();
		h.setZero();
		return 0;
	}

	// Dividing by the largest element first keeps the norm itself from overflowing or underflowing
	// (elements near the denormal range would square to zero). The result has Frobenius norm 1.
	btMatrix3x3 normalized;
	for (int i = 0; i < 3; ++i) normalized[i] = a[i] / largest;
	normalized = normalized * (btScalar(1) / btSqrt(frobeniusNorm2(normalized)));
	if (!(btFabs(normalized.determinant()) > SIMD_EPSILON))
	{
		u = orthogonalFactorOfSingular(normalized);
		h = symmetricPart(u.transposeTimes(a));
		return 0;
	}

	u = normalized;
	unsigned int iterations = 0;
	bool converged = false;
	while (iterations < m_maxIterations)
	{
		++iterations;
		// u^-T = adjoint^T / det; the iterates' singular values are at least 1 after the first step,
		// so det stays well away from 0.
		const btMatrix3x3 inverseTranspose = u.adjoint().transpose() * (btScalar(1) / u.determinant());
		btScalar scale = btScalar(1);
		if (!converged) scale = btSqrt(btSqrt(frobeniusNorm2(inverseTranspose) / frobeniusNorm2(u)));
		const btMatrix3x3 next = (u * scale + inverseTranspose * (btScalar(1) / scale)) * btScalar(0.5);
		const btScalar change2 = frobeniusNorm2(next - u);
		u = next;
		if (converged) break;  // that was the polishing step
		converged = change2 <= m_tolerance * m_tolerance * frobeniusNorm2(u);
	}
	h = symmetricPart(u.transposeTimes(a));
	return iterations;
}

unsigned int polarDecompose(const btMatrix3x3& a, btMatrix3x3& u, btMatrix3x3& h)
{
	return btPolarDecomposition().decompose(a, u, h);
}
