#pragma once
// Counter-based random numbers and the hemisphere sampling the estimators share.
#include <cmath>
#include <cstdint>

#include "svo/core/vec3.h"

namespace svo::reference {

// PCG's 64-bit LCG step followed by its RXS-M-XS output permutation
// (O'Neill 2014), used as a hash the way Jarzynski & Olano (JCGT 2020) use
// the 32-bit pcg_hash: well mixed for neighbouring inputs, a bijection.
inline uint64_t pcgHash(uint64_t x)
{
    const uint64_t state = x * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t word = ((state >> ((state >> 59u) + 5u)) ^ state) * 12605985483714917081ull;
    return (word >> 43u) ^ word;
}

// A PCG-RXS-M-XS generator whose state is the hash of (seed, item, sample):
// every sample of every pixel (or point) has its own stream, so results do
// not depend on which thread runs what.
class Rng {
public:
    Rng(uint64_t seed, uint64_t item, uint64_t sample)
        : state_(pcgHash(pcgHash(pcgHash(seed) ^ item) ^ sample))
    {
    }
    uint64_t nextBits()
    {
        state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
        const uint64_t word = ((state_ >> ((state_ >> 59u) + 5u)) ^ state_) * 12605985483714917081ull;
        return (word >> 43u) ^ word;
    }
    /// Uniform in [0, 1), 53 bits.
    double next() { return double(nextBits() >> 11) * 0x1.0p-53; }

private:
    uint64_t state_;
};

// An orthonormal basis (t, b, n) around a unit n, branchless and continuous
// except at n.z = 0 (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
inline void basis(const Vec3d& n, Vec3d& t, Vec3d& b)
{
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
}

// A cosine-weighted direction around unit n (density cos(theta)/pi): a
// uniform point on the unit disk lifted to the hemisphere (Malley's method).
inline Vec3d cosineDirection(const Vec3d& n, double u1, double u2)
{
    const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
    const double z = std::sqrt(std::fmax(0.0, 1.0 - u1));
    Vec3d t, b;
    basis(n, t, b);
    return (r * std::cos(phi)) * t + (r * std::sin(phi)) * b + z * n;
}

} // namespace svo::reference
