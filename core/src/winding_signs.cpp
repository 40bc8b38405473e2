// Winding-number signs on the CPU (svo/core/winding_signs.h): winding_walk.glsl's
// arithmetic, in the same order, for one point (brick centres) or for the
// 512 centres of a brick sharing one walk (winding_columns.comp's idea, a
// brick wide). Compiled with -ffp-contract=off: the float sums must be the
// GPU's, whose operations are `precise`.
#include "svo/core/winding_signs.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "svo/core/error.h"
#include "svo/core/gpu_layout.h"

namespace svo {
namespace {

constexpr float kInvFourPi = 0.0795774715459476679f;
constexpr float kPi = 3.14159265358979324f;
constexpr float kHalfPi = 1.57079632679489662f;

/// Tree levels the walk's stack holds: the GPU's (field_layout.h's
/// kWindingStack), so both paths refuse the same trees.
constexpr uint32_t kWalkStack = 64;

inline double dot3(const Vec3d& u, const Vec3d& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }

/// The arctangent of r in [0, 1], in float, as Mesa's GLSL compiler lowers
/// atan() for llvmpipe: an odd polynomial of degree 11 (absolute error about
/// 1e-5), its terms summed from the lowest. The C library's atanf was a third
/// of the walk's time and is no nearer a hardware GPU's own atan; with this
/// one the CPU's sums are llvmpipe's, and it vectorizes.
inline float atanUnit(float r)
{
    const float r2 = r * r, r3 = r2 * r, r5 = r3 * r2, r7 = r5 * r2, r9 = r7 * r2, r11 = r9 * r2;
    return r * 0.9999793128310355f + r3 * -0.3326756418091246f + r5 * 0.1938924977115610f +
           r7 * -0.1173503194786851f + r9 * 0.0536813784310406f + r11 * -0.0121323213173444f;
}

/// Solid angle of a triangle whose corners, relative to the point, are x, y,
/// z (winding_walk.glsl's, without branches so that a loop over centres
/// vectorizes: the same value as the GLSL's branches select).
inline float solidAngle(const Vec3d& x, const Vec3d& y, const Vec3d& z)
{
    const double lx = std::sqrt(dot3(x, x)), ly = std::sqrt(dot3(y, y)), lz = std::sqrt(dot3(z, z));
    const double det = dot3(x, cross(y, z));
    const double den = lx * ly * lz + dot3(x, y) * lz + dot3(y, z) * lx + dot3(z, x) * ly;
    // Half the angle is atan2(det, den), built as the GPU builds it: the
    // float arctangent of a ratio in [0, 1], its quadrant chosen here.
    const double ad = std::abs(det), aden = std::abs(den);
    const bool low = ad <= aden;
    const float at = atanUnit(float(low ? ad / aden : aden / ad));
    const float base = low ? at : kHalfPi - at;
    const float angle = den >= 0.0 ? base : kPi - base;
    const float signedAngle = det > 0.0 ? 2.0f * angle : -2.0f * angle;
    return det == 0.0 ? 0.0f : signedAngle; // 0: the point in the triangle's plane
}

/// One row i of the second moments added to the second-order sums.
inline void addSecondMoments(float s00, float s01, float s02, float s11, float s12, float s22, float dx, float dy,
                             float dz, float di, float sdi, float& a, float& b, float& c)
{
    const float sdx = s00 * dx + s01 * dy + s02 * dz, sdy = s01 * dx + s11 * dy + s12 * dz,
                sdz = s02 * dx + s12 * dy + s22 * dz;
    a = a + sdi;
    b = b + di * (s00 + s11 + s22);
    c = c + di * (dx * sdx + dy * sdy + dz * sdz);
}

/// A far node's term (times 4 pi) at d = c - q, d2 = |d|^2; `e` is the node's
/// floats from the area vector on (winding_tree.h's layout: N, C, M).
inline float farTerm(float dx, float dy, float dz, float d2, const float* e)
{
    // e[0..2] N, e[3] C_00, e[4..7] C_01 C_02 C_10 C_11, e[8..11] C_12 C_20
    // C_21 C_22, then M: e[12..15] M_000 M_001 M_002 M_011, e[16..19] M_012
    // M_022 M_100 M_101, e[20..23] M_102 M_111 M_112 M_122, e[24..27] M_200
    // M_201 M_202 M_211, e[28..29] M_212 M_222.
    const float cdx = e[3] * dx + e[4] * dy + e[5] * dz, cdy = e[6] * dx + e[7] * dy + e[8] * dz,
                cdz = e[9] * dx + e[10] * dy + e[11] * dz;
    const float inv3 = 1.0f / (d2 * std::sqrt(d2));
    const float inv5 = inv3 / d2;
    float a = 0.0f, b = 0.0f, c = 0.0f;
    addSecondMoments(e[12], e[13], e[14], e[15], e[16], e[17], dx, dy, dz, dx, e[12] * dx + e[13] * dy + e[14] * dz,
                     a, b, c);
    addSecondMoments(e[18], e[19], e[20], e[21], e[22], e[23], dx, dy, dz, dy, e[19] * dx + e[21] * dy + e[22] * dz,
                     a, b, c);
    addSecondMoments(e[24], e[25], e[26], e[27], e[28], e[29], dx, dy, dz, dz, e[26] * dx + e[28] * dy + e[29] * dz,
                     a, b, c);
    const float first = ((dx * e[0] + dy * e[1] + dz * e[2]) + (e[3] + e[7] + e[11])) * inv3 -
                        3.0f * (dx * cdx + dy * cdy + dz * cdz) * inv5;
    const float second = 0.5f * (15.0f * c * inv5 / d2 - 3.0f * (2.0f * a + b) * inv5);
    return first + second;
}

/// What every walk reads.
struct Walk {
    const WindingTree& tree;
    float beta2;

    /// Whether node n is farther than beta radii from qf; if so adds its term.
    bool far(uint32_t n, float qx, float qy, float qz, float& sum) const
    {
        const float* cr = &tree.nodes[size_t(kWindingNodeFloats) * n];
        const float dx = cr[0] - qx, dy = cr[1] - qy, dz = cr[2] - qz;
        const float d2 = dx * dx + dy * dy + dz * dz;
        const float reach2 = beta2 * cr[3] * cr[3];
        if (!(d2 > reach2)) return false;
        sum += farTerm(dx, dy, dz, d2, cr + 4);
        return true;
    }

    float triangleAt(uint32_t t, const Vec3d& q) const
    {
        const auto& f = tree.triangles[t];
        const auto& p = tree.positions;
        return solidAngle(p[f[0]] - q, p[f[1]] - q, p[f[2]] - q);
    }

    /// The winding number at q (winding_number.comp's windingNumber).
    float at(const Vec3d& q) const
    {
        const float qx = float(q.x), qy = float(q.y), qz = float(q.z);
        uint32_t stack[2 * kWalkStack + 2];
        uint32_t top = 1;
        stack[0] = 0;
        float sum = 0.0f;
        while (top > 0) {
            const uint32_t n = stack[--top];
            if (far(n, qx, qy, qz, sum)) continue;
            const uint32_t l0 = tree.links[2 * size_t(n)], l1 = tree.links[2 * size_t(n) + 1];
            if (l1 & gpu::kWindingLeaf) {
                const uint32_t last = l0 + (l1 & ~gpu::kWindingLeaf);
                for (uint32_t i = l0; i < last; ++i) sum += triangleAt(tree.order[i], q);
            } else {
                stack[top++] = l0;
                stack[top++] = l1;
            }
        }
        return sum * kInvFourPi;
    }

    /// The winding numbers (times 4 pi) of the centres of the brick at
    /// `origin` that `mask` selects, in `sum` (the others 0): one walk for
    /// them all, each node visited for the mask of centres whose own walk
    /// reaches it, in the order their own walks would visit it. The centres
    /// of a mask are gathered into a list first, and a node's far terms or
    /// a leaf triangle's solid angles are computed over the list in one loop
    /// the compiler vectorizes (the same IEEE operations, lane by lane), then
    /// added to each centre's sum: only the centres whose walk reaches a
    /// node pay for it. A node that all 512 reach skips the list.
    // AVX2 where the CPU has it: twice the lanes, the same IEEE operations
    // (no FMA: -ffp-contract=off), so the same bits.
    __attribute__((target_clones("avx2", "default"))) void sums(const std::array<uint32_t, 3>& origin,
                                                                const Brick& mask, float* sum) const
    {
        struct Entry {
            uint32_t node;
            uint64_t mask[8];
        };
        Entry stack[2 * kWalkStack + 2];
        alignas(64) float qx[512], qy[512], qz[512];
        // The gathered centres of the node at hand: their index, coordinates
        // (float for far terms, double for solid angles) and term.
        alignas(64) uint32_t lane[512];
        alignas(64) float gx[512], gy[512], gz[512], term[512];
        alignas(64) double hx[512], hy[512], hz[512];
        alignas(64) int32_t isFar[512];
        std::fill(sum, sum + 512, 0.0f);
        for (uint32_t v = 0; v < 512; ++v) {
            qx[v] = float(origin[0] + (v >> 6));
            qy[v] = float(origin[1] + ((v >> 3) & 7));
            qz[v] = float(origin[2] + (v & 7));
        }
        if (mask.count() == 0) return;
        uint32_t top = 1;
        stack[0].node = 0;
        std::copy(mask.words, mask.words + 8, stack[0].mask);
        while (top > 0) {
            const Entry e = stack[--top];
            const float* cr = &tree.nodes[size_t(kWindingNodeFloats) * e.node];
            const float* ex = cr + 4;
            const float reach2 = beta2 * cr[3] * cr[3];
            uint64_t near[8] = {};
            uint32_t nearCount = 0;
            bool full = true;
            for (int w = 0; w < 8; ++w) full &= e.mask[w] == ~uint64_t(0);
            if (full) {
                // Every centre reached (the tree's upper levels): no list to
                // gather; the centres that are near add 0.
                for (uint32_t v = 0; v < 512; ++v) {
                    const float dx = cr[0] - qx[v], dy = cr[1] - qy[v], dz = cr[2] - qz[v];
                    const float d2 = dx * dx + dy * dy + dz * dz;
                    isFar[v] = d2 > reach2 ? -1 : 0;
                    const float t = farTerm(dx, dy, dz, d2, ex);
                    sum[v] += isFar[v] ? t : 0.0f;
                }
                for (uint32_t v = 0; v < 512; ++v)
                    if (!isFar[v]) near[v >> 6] |= uint64_t(1) << (v & 63), lane[nearCount++] = v;
            } else {
                uint32_t count = 0;
                for (int w = 0; w < 8; ++w)
                    for (uint64_t m = e.mask[w]; m; m &= m - 1) {
                        const uint32_t v = uint32_t(64 * w + __builtin_ctzll(m));
                        lane[count] = v, gx[count] = qx[v], gy[count] = qy[v], gz[count] = qz[v];
                        ++count;
                    }
                for (uint32_t i = 0; i < count; ++i) {
                    const float dx = cr[0] - gx[i], dy = cr[1] - gy[i], dz = cr[2] - gz[i];
                    const float d2 = dx * dx + dy * dy + dz * dz;
                    isFar[i] = d2 > reach2 ? -1 : 0;
                    term[i] = farTerm(dx, dy, dz, d2, ex);
                }
                // The near centres, compacted in place (in mask order still).
                for (uint32_t i = 0; i < count; ++i) {
                    const uint32_t v = lane[i];
                    if (isFar[i]) {
                        sum[v] += term[i];
                    } else {
                        near[v >> 6] |= uint64_t(1) << (v & 63);
                        lane[nearCount++] = v;
                    }
                }
            }
            if (nearCount == 0) continue;
            const uint32_t l0 = tree.links[2 * size_t(e.node)], l1 = tree.links[2 * size_t(e.node) + 1];
            if (l1 & gpu::kWindingLeaf) {
                // The near centres' sums gathered once for the leaf's
                // triangles (each still adds its angles in the walk's order).
                for (uint32_t i = 0; i < nearCount; ++i) {
                    hx[i] = double(qx[lane[i]]), hy[i] = double(qy[lane[i]]), hz[i] = double(qz[lane[i]]);
                    term[i] = sum[lane[i]];
                }
                const uint32_t last = l0 + (l1 & ~gpu::kWindingLeaf);
                for (uint32_t j = l0; j < last; ++j) {
                    const auto& f = tree.triangles[tree.order[j]];
                    const Vec3d a = tree.positions[f[0]], b = tree.positions[f[1]], c = tree.positions[f[2]];
                    for (uint32_t i = 0; i < nearCount; ++i) {
                        const Vec3d q{hx[i], hy[i], hz[i]};
                        term[i] += solidAngle(a - q, b - q, c - q);
                    }
                }
                for (uint32_t i = 0; i < nearCount; ++i) sum[lane[i]] = term[i];
            } else {
                stack[top].node = l0;
                std::copy(near, near + 8, stack[top++].mask);
                stack[top].node = l1;
                std::copy(near, near + 8, stack[top++].mask);
            }
        }
    }

    /// The inside voxels of the brick at `origin`: all 512 centres walked.
    Brick brick(const std::array<uint32_t, 3>& origin) const
    {
        Brick all;
        std::fill(all.words, all.words + 8, ~uint64_t(0));
        alignas(64) float sum[512];
        sums(origin, all, sum);
        Brick inside;
        for (uint32_t v = 0; v < 512; ++v)
            if (sum[v] * kInvFourPi >= 0.5f) inside.words[v >> 6] |= uint64_t(1) << (v & 63);
        return inside;
    }
};

/// beta^2 in float; +infinity as the largest float, which no squared distance exceeds.
float beta2Of(double beta)
{
    if (!(beta > 0)) throw InvalidInput(fmt::format("a winding accuracy (beta) of {}: it must be positive", beta));
    const double b2 = beta * beta;
    return b2 < 3.0e38 ? float(b2) : 3.0e38f;
}

void checkDepth(const WindingTree& tree)
{
    if (tree.depth + 1 > kWalkStack)
        throw Unsupported(fmt::format("a winding tree {} levels deep is more than the walk's stack holds ({})",
                                      tree.depth + 1, kWalkStack));
}

} // namespace

namespace {

/// A brick centre's local coordinates (x-fastest over a box of d bricks from brick o).
Vec3d brickCentre(uint64_t g, const std::array<uint64_t, 3>& d, const std::array<uint32_t, 3>& o = {0, 0, 0})
{
    const uint64_t x = o[0] + g % d[0], y = o[1] + g / d[0] % d[1], z = o[2] + g / (d[0] * d[1]);
    return Vec3d{double(8 * x) + 3.5, double(8 * y) + 3.5, double(8 * z) + 3.5};
}

/// Whether every number in [lo, hi] falls in one class of bricksBeyondBand.
bool oneClass(double lo, double hi)
{
    return hi < 0.5 - kWindingMargin || (lo > 0.5 - kWindingMargin && hi < 0.5 + kWindingMargin) ||
           lo > 0.5 + kWindingMargin;
}

/// How far a climbed number may still move and stay in its class.
double classRoom(double value)
{
    return std::max({0.5 - kWindingMargin - value, value - 0.5 - kWindingMargin,
                     std::min(value - 0.5 + kWindingMargin, 0.5 + kWindingMargin - value)});
}

/// A climbed number's doubt as a float that bounds it, with the rounding of
/// the number to float.
float doubtOfFloat(double value, double doubt)
{
    const double d = doubt + 1e-6 * (1.0 + std::abs(value));
    const float f = float(d);
    return double(f) < d ? std::nextafter(f, INFINITY) : f;
}

/// Brick centres column by column: the lowest walked, each above climbed
/// from the one below where the climb keeps it in one class (its doubt plus
/// `allowance` either way; a step's slope bounded only as far as it could
/// still decide), else walked; with `climb` false every centre walked.
/// @return the centres walked
uint64_t climbColumn(const Walk& walk, const BrickCentreColumns& columns, uint64_t column, double allowance,
                     bool climb, std::vector<float>& out, std::vector<float>* doubts)
{
    const std::array<uint64_t, 3> d{columns.dims[0], columns.dims[1], columns.dims[2]};
    const uint64_t plane = d[0] * d[1];
    uint64_t walked = 0;
    double value = 0, doubt = 0;
    for (uint64_t z = 0; z < d[2]; ++z) {
        const uint64_t g = column + plane * z;
        if (z > 0 && climb) {
            value += columns.jump[g];
            const double room = classRoom(value) - allowance - doubt;
            if (room > 0) {
                doubt += 8.0 * double(columns.slopeAt(g, room / 8.0));
                if (oneClass(value - doubt - allowance, value + doubt + allowance)) {
                    out[g] = float(value);
                    if (doubts) (*doubts)[g] = doubtOfFloat(value, doubt);
                    continue;
                }
            }
        }
        out[g] = walk.at(brickCentre(g, d, columns.origin));
        value = double(out[g]), doubt = 0;
        ++walked;
    }
    return walked;
}

} // namespace

std::vector<float> windingAtBrickCentres(const WindingTree& tree, const GridSpec& grid, double beta,
                                         const Checkpoint& checkpoint, const BrickCentreColumns* columns,
                                         uint64_t* walked, std::vector<float>* doubts)
{
    checkDepth(tree);
    const Walk walk{tree, beta2Of(beta)};
    std::array<uint64_t, 3> d{};
    for (int a = 0; a < 3; ++a) d[a] = columns ? columns->dims[a] : (grid.dims[a] + 7) / 8;
    const uint64_t n = d[0] * d[1] * d[2];
    if (n > (uint64_t(1) << 31))
        throw Unsupported(fmt::format("the grid's box holds {} bricks, more than the winding pass evaluates (2^31); use a "
                                      "coarser grid",
                                      n));
    if (columns && columns->jump.size() != n)
        throw InvalidInput(fmt::format("windingAtBrickCentres: {} bricks but columns for {}", n, columns->jump.size()));
    std::vector<float> out(n);
    if (doubts) doubts->assign(n, 0.0f);
    if (!columns) {
        constexpr uint64_t kBatch = 1 << 14;
        for (uint64_t first = 0; first < n; first += kBatch) {
            const uint64_t last = std::min(n, first + kBatch);
            tbb::parallel_for(tbb::blocked_range<uint64_t>(first, last, 64), [&](const tbb::blocked_range<uint64_t>& r) {
                for (uint64_t g = r.begin(); g != r.end(); ++g) out[g] = walk.at(brickCentre(g, d));
            });
            checkpoint(double(last) / double(n), "winding per brick");
        }
        if (walked) *walked = n;
        return out;
    }
    // A climb that walks most centres anyway costs more than walking them
    // all (the bounds it asks for near the boundary): once half of the
    // centres so far were walked, the other columns walk every centre.
    const double allowance = 2.0 * windingWalkError(beta);
    const uint64_t plane = d[0] * d[1];
    std::atomic<uint64_t> centres{0};
    constexpr uint64_t kBatch = 256;
    for (uint64_t first = 0; first < plane; first += kBatch) {
        const uint64_t last = std::min(plane, first + kBatch);
        const bool climb = 2 * centres.load() <= first * d[2];
        tbb::parallel_for(tbb::blocked_range<uint64_t>(first, last, 16), [&](const tbb::blocked_range<uint64_t>& r) {
            uint64_t here = 0;
            for (uint64_t c = r.begin(); c != r.end(); ++c) here += climbColumn(walk, *columns, c, allowance, climb, out, doubts);
            centres += here;
        });
        checkpoint(double(last) / double(plane), "winding per brick");
    }
    if (walked) *walked = centres;
    return out;
}

std::vector<Brick> windingInside(const WindingTree& tree, const std::vector<BrickCoord>& bricks, double beta,
                                 const Checkpoint& checkpoint)
{
    checkDepth(tree);
    const Walk walk{tree, beta2Of(beta)};
    std::vector<Brick> out(bricks.size());
    constexpr size_t kBatch = 256;
    for (size_t first = 0; first < bricks.size(); first += kBatch) {
        const size_t last = std::min(bricks.size(), first + kBatch);
        tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 1), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i)
                out[i] = walk.brick({8 * bricks[i][0], 8 * bricks[i][1], 8 * bricks[i][2]});
        });
        checkpoint(double(last) / double(bricks.size()), "winding per voxel");
    }
    return out;
}

namespace {

/// The winding numbers of one run of bricks stacked in z, climbed from the
/// centres of its lowest layer (walked) by windingColumns' jumps and slopes;
/// the centres the climb cannot decide are walked.
class Climb {
public:
    Climb(const Walk& walk, const WindingColumns& columns, float allowance, const ClimbAnchors* anchors)
        : walk_(walk), columns_(columns), allowance_(allowance), anchors_(anchors)
    {
    }

    /// Classifies bricks[run[0]], bricks[run[1]], ... (z rising by one).
    /// @return the centres walked
    uint64_t run(const std::vector<BrickCoord>& bricks, const uint32_t* run, size_t count, std::vector<Brick>& inside)
    {
        uint64_t walked = 0;
        for (size_t k = 0; k < count; ++k) {
            const uint32_t i = run[k];
            const std::array<uint32_t, 3> origin{8 * bricks[i][0], 8 * bricks[i][1], 8 * bricks[i][2]};
            jumpsOf(i);
            Brick known, walk, out;
            if (k == 0 && !fromBelow(bricks[i])) // the lowest layer, walked, anchors every column
                for (uint32_t x = 0; x < 8; ++x) walk.words[x] = 0x0101010101010101ull;
            // Rounds: walk what the last climb could not decide, then climb
            // again from every walked centre. Past a centre it cannot decide
            // a climb goes on as if the walk will find the number it expected
            // there, marking where it would walk next: most columns need one
            // round, not one per centre.
            do {
                if (walk.count()) {
                    walk_.sums(origin, walk, sum_);
                    walked += walk.count();
                    for (uint32_t w = 0; w < 8; ++w) {
                        for (uint64_t m = walk.words[w]; m; m &= m - 1) {
                            const uint32_t v = 64 * w + uint32_t(__builtin_ctzll(m));
                            exact_[v] = double(sum_[v] * kInvFourPi);
                            inside_[v] = sum_[v] * kInvFourPi >= 0.5f;
                        }
                        known.words[w] |= walk.words[w];
                    }
                }
                walk = Brick{};
                out = Brick{};
                for (uint32_t c = 0; c < 64; ++c) climb(i, c, known, walk, out);
            } while (walk.count());
            std::copy(topValue_, topValue_ + 64, value_);
            std::copy(topDoubt_, topDoubt_ + 64, doubt_);
            inside[i] = out;
        }
        return walked;
    }

private:
    /// Enters brick @a b's columns from the brick below, when ClimbAnchors
    /// vouches that its box holds no triangle: the number at its centre,
    /// give or take its doubt and the gradient's bound over the 3.5 sqrt 3
    /// voxels (at most) to the top centre of any of its columns. False
    /// (the lowest layer is walked) where that could not decide a side.
    bool fromBelow(const BrickCoord& b)
    {
        if (!anchors_ || b[2] == 0) return false;
        const BrickCoord below{b[0], b[1], b[2] - 1};
        const auto& o = anchors_->columns->origin;
        const auto& d = anchors_->columns->dims;
        for (int a = 0; a < 3; ++a)
            if (below[a] < anchors_->lo[a] || below[a] >= anchors_->hi[a] || below[a] < o[a] || below[a] - o[a] >= d[a])
                return false;
        const uint64_t g = (below[0] - o[0]) + uint64_t(d[0]) * ((below[1] - o[1]) + uint64_t(d[1]) * (below[2] - o[2]));
        constexpr double kFarthest = 6.0622; // 3.5 sqrt 3, rounded up
        const double value = double((*anchors_->centres)[g]);
        const double doubt = double((*anchors_->doubts)[g]) + kFarthest * double(anchors_->columns->gradientAt(g));
        if (!(std::abs(value - 0.5) > doubt + 2.0 * allowance_)) return false;
        std::fill(value_, value_ + 64, value);
        std::fill(doubt_, doubt_ + 64, doubt);
        return true;
    }

    /// Climbs column c of brick i from the brick below (value_, doubt_), or
    /// from its known centres: sets the inside voxels decided, marks in
    /// `walk` those to walk, and keeps the number and doubt at its top (for
    /// the brick above, once a round marks nothing).
    void climb(uint32_t i, uint32_t c, const Brick& known, Brick& walk, Brick& out)
    {
        const double slope = columns_.slopeAt(i, c);
        double value = value_[c], doubt = doubt_[c];
        bool expected = false; // past a centre marked this round
        for (uint32_t z = 0; z < 8; ++z) {
            const uint32_t v = 8 * c + z;
            const uint64_t bit = uint64_t(1) << (v & 63);
            if (known.words[v >> 6] & bit) {
                value = exact_[v], doubt = 0.0, expected = false;
                if (inside_[v]) out.words[v >> 6] |= bit;
                continue;
            }
            value += jump_[v];
            doubt += slope;
            if (std::abs(value - 0.5) > doubt + 2.0 * allowance_) {
                if (!expected && value >= 0.5) out.words[v >> 6] |= bit;
                continue;
            }
            walk.words[v >> 6] |= bit;
            doubt = 0.0, expected = true;
        }
        topValue_[c] = value, topDoubt_[c] = doubt;
    }

    /// Brick i's jumps, one a voxel (0 where none).
    void jumpsOf(uint32_t i)
    {
        std::fill(jump_, jump_ + 512, 0);
        for (uint32_t j = columns_.first[i]; j < columns_.first[i + 1]; ++j)
            jump_[columns_.jumps[j].voxel] = columns_.jumps[j].jump;
    }

    const Walk& walk_;
    const WindingColumns& columns_;
    float allowance_;
    const ClimbAnchors* anchors_;
    alignas(64) float sum_[512];
    double exact_[512];
    bool inside_[512];
    int32_t jump_[512];
    double value_[64], doubt_[64];       // per column, entering the brick from below
    double topValue_[64], topDoubt_[64]; // ... and at its top
};

} // namespace

float windingWalkError(double beta)
{
    const double scaled = 0.1 * std::pow(1.5 / beta, 3.0);
    return float(std::clamp(scaled, 1e-3, 0.5));
}

std::vector<Brick> windingInsideAlongColumns(const WindingTree& tree, const std::vector<BrickCoord>& bricks,
                                             const WindingColumns& columns, double beta, const Checkpoint& checkpoint,
                                             uint64_t* walked, const ClimbAnchors* anchors)
{
    checkDepth(tree);
    if (columns.slope.size() != bricks.size() || columns.columnsAt.size() != bricks.size() ||
        columns.first.size() != bricks.size() + 1)
        throw InvalidInput(fmt::format("windingInsideAlongColumns: {} bricks but columns for {}", bricks.size(),
                                       columns.slope.size()));
    if (anchors) {
        const auto& d = anchors->columns->dims;
        const uint64_t n = uint64_t(d[0]) * d[1] * d[2];
        if (anchors->centres->size() != n || anchors->doubts->size() != n)
            throw InvalidInput(fmt::format("windingInsideAlongColumns: anchors for {} of a box of {} bricks",
                                           anchors->centres->size(), n));
    }
    const Walk walk{tree, beta2Of(beta)};
    // Runs: bricks of one brick column with consecutive z, lowest first.
    std::vector<uint32_t> order(bricks.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    tbb::parallel_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return bricks[a] < bricks[b]; });
    std::vector<size_t> runStart;
    for (size_t n = 0; n < order.size(); ++n) {
        const auto &p = bricks[order[n]], &q = n ? bricks[order[n - 1]] : p;
        if (n == 0 || p[0] != q[0] || p[1] != q[1] || p[2] != q[2] + 1) runStart.push_back(n);
    }
    runStart.push_back(order.size());
    std::vector<Brick> out(bricks.size());
    std::atomic<uint64_t> centres{0};
    const float allowance = windingWalkError(beta);
    tbb::enumerable_thread_specific<std::unique_ptr<Climb>> climbs(
        [&] { return std::make_unique<Climb>(walk, columns, allowance, anchors); });
    const size_t runs = runStart.size() - 1;
    constexpr size_t kBatch = 256;
    for (size_t first = 0; first < runs; first += kBatch) {
        const size_t last = std::min(runs, first + kBatch);
        tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 1), [&](const tbb::blocked_range<size_t>& r) {
            Climb& climb = *climbs.local();
            uint64_t here = 0;
            for (size_t k = r.begin(); k != r.end(); ++k)
                here += climb.run(bricks, order.data() + runStart[k], runStart[k + 1] - runStart[k], out);
            centres += here;
        });
        checkpoint(double(last) / double(runs), "winding per voxel");
    }
    if (walked) *walked = centres;
    return out;
}

BricksBeyondBand bricksBeyondBand(const std::vector<float>& centres, const std::array<uint32_t, 3>& d,
                                  const std::vector<BrickCoord>& band, const std::array<uint32_t, 3>& origin)
{
    // `band` is sorted: the box's bricks in x-major order walk it once.
    BricksBeyondBand out;
    size_t next = 0;
    for (uint32_t x = 0; x < d[0]; ++x)
        for (uint32_t y = 0; y < d[1]; ++y)
            for (uint32_t z = 0; z < d[2]; ++z) {
                const BrickCoord b{origin[0] + x, origin[1] + y, origin[2] + z};
                while (next < band.size() && band[next] < b) ++next; // band bricks outside the box
                if (next < band.size() && band[next] == b) {
                    ++next;
                    continue;
                }
                const float w = centres[x + size_t(d[0]) * (y + size_t(d[1]) * z)];
                if (std::abs(w - 0.5f) < kWindingMargin) out.voxelwise.push_back(b);
                else if (w >= 0.5f) out.inside.push_back(b);
            }
    return out;
}

} // namespace svo
