// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef POLARDECOMPOSITION_H
#define POLARDECOMPOSITION_H

/// btPolarDecomposition: splits a 3x3 matrix into a rotation-like and a stretch part, a = u * h.
///
/// u is orthogonal and h symmetric positive semi-definite. When det(a) > 0, u is a rotation
/// (det +1); when det(a) < 0 it is a rotation combined with a reflection (det -1).
///
/// Method: a is first divided by its Frobenius norm (so the result does not depend on its scale and
/// nothing overflows or underflows), then the scaled Newton iteration u <- (g u + u^-T / g) / 2,
/// g = sqrt(|u^-1|_F / |u|_F), runs until one step changes u by at most tolerance (relative,
/// Frobenius norm); one more unscaled step then brings u to rounding level, because the iteration
/// converges quadratically. h = u^T a, made exactly symmetric.
///
/// Singular input (|det| at most SIMD_EPSILON times the cube of the Frobenius norm, where Newton's
/// inverse is meaningless): u comes from the eigenvectors of a^T a instead, completed to a rotation
/// (det +1) in the directions a maps to zero, and decompose() returns 0. The zero matrix and input
/// with a non-finite element give u = identity and h = zero, also returning 0. No input gives NaN.

#include "LinearMath/btMatrix3x3.h"

/// Computes the polar decomposition a = u * h of 3x3 matrices.
class btPolarDecomposition
{
public:
	/// Default convergence tolerance: the relative change of u in one step.
	static const btScalar DEFAULT_TOLERANCE;
	/// Default limit on the Newton steps (scaled Newton needs under 10 even at condition 1e16).
	static const unsigned int DEFAULT_MAX_ITERATIONS;

	/// A decomposer with the given tolerance (relative change of u per step) and step limit.
	btPolarDecomposition(btScalar tolerance = DEFAULT_TOLERANCE, unsigned int maxIterations = DEFAULT_MAX_ITERATIONS);

	/// Writes u (orthogonal) and h (symmetric positive semi-definite) with a = u * h. Returns the Newton
	/// steps taken (at most maxIterations(); 0 for singular, zero or non-finite input).
	unsigned int decompose(const btMatrix3x3& a, btMatrix3x3& u, btMatrix3x3& h) const;

	/// The step limit given at construction.
	unsigned int maxIterations() const;

private:
	btScalar m_tolerance;
	unsigned int m_maxIterations;
};

/// btPolarDecomposition().decompose(a, u, h) with the default tolerance and step limit.
unsigned int polarDecompose(const btMatrix3x3& a, btMatrix3x3& u, btMatrix3x3& h);

#endif  // POLARDECOMPOSITION_H
