// The procedural city (city_scene.h): planned block by block on one core,
// then written on all cores into arrays sized from the plan.
//
// Built with -ffp-contract=off (core/CMakeLists.txt): with only +, -, *, /
// and sqrt, each correctly rounded and never fused, every coordinate is the
// same on every platform and compiler.
#include "svo/core/city_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <tbb/parallel_for.h>
#include <utility>
#include <variant>
#include <vector>

#include "svo/core/error.h"

namespace svo {
namespace {

// ---------------------------------------------------------------------------
// Random numbers that are the same everywhere. std::uniform_*_distribution is
// implementation-defined and std::rand differs between C libraries, so the
// city uses splitmix64 (Steele, Lea and Flood, "Fast splittable pseudorandom
// number generators", 2014) and makes doubles from its bits by integer
// arithmetic.

/// splitmix64's output function: a bijection of 64-bit words that mixes every bit.
constexpr uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

class Random {
public:
    explicit Random(uint64_t state) : state_(state) {}
    uint64_t next() { return mix64(state_ += 0x9e3779b97f4a7c15ull); }
    /// In [0, 1): the top 53 bits times 2^-53, exact.
    double unit() { return double(next() >> 11) * 0x1p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
    /// A whole number in [lo, hi]; the modulo's bias is below 2^-60 here.
    int between(int lo, int hi) { return lo + int(next() % uint64_t(hi - lo + 1)); }
    bool chance(double p) { return unit() < p; }

private:
    uint64_t state_;
};

/// Each block has a stream of its own, so that its contents depend on the
/// seed and its number only, never on how much was drawn before it.
Random blockRandom(uint64_t seed, uint64_t block) { return Random(mix64(mix64(seed) ^ block)); }

// ---------------------------------------------------------------------------
// The plan: each block's parts as a few numbers each, with the exact vertex
// and triangle counts each part will write. Metres, y up.

constexpr double kPitch = 120;       ///< block to block
constexpr double kRoad = 16;         ///< the road strips on a block's low x and z sides
constexpr double kGutter = 0.25;     ///< kept free around roads: no road vertex meets another part's
constexpr double kSidewalk = 3;      ///< the curb ring's width
constexpr double kCurb = 0.15;       ///< the curb's height
constexpr double kSill = 0.9;        ///< floor to window
constexpr double kWindowHeight = 1.5;
constexpr double kRecess = 0.3;      ///< how deep windows sit in a facade
constexpr double kPier = 0.8;        ///< least facade between windows and at corners: more than kRecess
constexpr double kTrunkFoot = 0.05;  ///< trunks start inside the curb, not on its bottom face
constexpr int kCrownFaces = 80;      ///< an icosahedron with each face cut in four
constexpr int kMissingFaces = 4;     ///< left out of each crown, so that it is open

struct Rect {
    double x0, z0, x1, z1;
    Rect shrunk(double d) const { return {x0 + d, z0 + d, x1 - d, z1 - d}; }
};

/// A flat strip on y = 0 (open), in `pieces` quads along its longer side.
struct Road {
    Rect area;
    int pieces;
};
/// A closed box standing on y = 0 whose facades have `floors` rows of
/// recessed windows, `columnsX` on the faces along x and `columnsZ` on the
/// others; without floors, a plain box.
struct Building {
    Rect footprint;
    int columnsX, columnsZ, floors;
    double floorHeight, windowWidth, top;
};
/// A closed box: a garden wall.
struct Slab {
    Rect area;
    double y0, y1;
};
/// A closed rectangular ring `wall` thick: a courtyard building, or the curb.
struct Ring {
    Rect outer;
    double y0, y1, wall;
};
/// An open hexagonal trunk up to the centre of a crown that is a soup of
/// kCrownFaces - kMissingFaces triangles, each on vertices of its own.
struct Tree {
    double x, z, trunkRadius, trunkTop, crownRadius, crownHeight;
    std::array<uint8_t, kMissingFaces> missing;
};
using Part = std::variant<Road, Building, Slab, Ring, Tree>;

struct Size {
    uint64_t vertices = 0, triangles = 0;
    Size& operator+=(Size s)
    {
        vertices += s.vertices;
        triangles += s.triangles;
        return *this;
    }
    bool operator==(Size s) const { return vertices == s.vertices && triangles == s.triangles; }
};

struct Block {
    double x = 0, z = 0;    ///< the low corner of its grid cell
    std::vector<Part> parts;
    Size size;              ///< of its parts
    Size first;             ///< its first vertex and triangle in the mesh
};

Block planBlock(uint64_t seed, uint64_t index);
Size sizeOf(const Part& part);
void writeBlock(const Block& block, TriangleMesh& mesh);

/// The parts of @a parts that fit in @a room triangles, in order.
Size keepWhatFits(std::vector<Part>& parts, uint64_t room)
{
    std::vector<Part> fit;
    Size kept;
    for (Part& p : parts)
        if (const Size s = sizeOf(p); kept.triangles + s.triangles <= room) {
            kept += s;
            fit.push_back(std::move(p));
        }
    parts = std::move(fit);
    return kept;
}

/// Whole blocks while they fit in @a target triangles; then, since one large
/// tower can leave much of the room unused, the parts that fit of as many
/// more blocks as it takes to come within 1% of the target (or until a block
/// has nothing small enough). A larger city is a smaller one with blocks
/// added, its last ones complete.
std::vector<Block> planCity(uint64_t seed, uint64_t target)
{
    std::vector<Block> blocks;
    Size total;
    bool cut = false; // a block has been cut short: the city is being finished
    for (uint64_t k = 0;; ++k) {
        Block b = planBlock(seed, k);
        for (const Part& p : b.parts) b.size += sizeOf(p);
        const uint64_t room = target - total.triangles;
        if (b.size.triangles > room) {
            cut = true;
            b.size = keepWhatFits(b.parts, room);
        }
        if (b.parts.empty()) return blocks;
        b.first = total;
        total += b.size;
        blocks.push_back(std::move(b));
        if (cut && target - total.triangles <= target / 100) return blocks;
    }
}

/// 1234567 -> "1,234,567"
std::string grouped(uint64_t n)
{
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

} // namespace

void checkCityTriangles(int64_t n, const std::string& name)
{
    if (n < 1'000 || n > 1'000'000'000)
        throw InvalidInput(name, fmt::format("must be a whole number from 1,000 to 1,000,000,000, got {}", n));
}

void checkCitySeed(int64_t, const std::string&) {}

TriangleMesh cityScene(const CityOptions& options)
{
    checkCityTriangles(int64_t(std::min<uint64_t>(options.triangles, INT64_MAX)), "CityOptions::triangles");
    const std::vector<Block> blocks = planCity(options.seed, options.triangles);
    Size total;
    for (const Block& b : blocks) total += b.size;
    if (total.vertices > std::numeric_limits<uint32_t>::max())
        throw std::logic_error("cityScene: more vertices than 32-bit indices reach"); // the rule's bound prevents it

    TriangleMesh mesh;
    mesh.source = fmt::format("city (seed {}, {} triangles)", options.seed, grouped(options.triangles));
    mesh.positions.resize(total.vertices);
    mesh.triangles.resize(total.triangles);
    // Each block writes its own slices, known from the plan: the result is
    // the same on any number of threads.
    tbb::parallel_for(size_t(0), blocks.size(), [&](size_t i) { writeBlock(blocks[i], mesh); });
    return mesh;
}

namespace {

// ---------------------------------------------------------------------------
// Planning a block: its grid cell, roads, curb, street trees and lots.

/// The cell of block @a k: the blocks of shell s (s*s to (s+1)^2 - 1) go up
/// column s, then back along row s, so the first n*n blocks fill an n x n square.
std::pair<uint64_t, uint64_t> blockCell(uint64_t k)
{
    uint64_t s = uint64_t(std::sqrt(double(k)));
    while (s * s > k) --s; // the double's rounding, either way
    while ((s + 1) * (s + 1) <= k) ++s;
    const uint64_t r = k - s * s;
    return r <= s ? std::pair{s, r} : std::pair{r - s - 1, s};
}

void addRoadsAndCurb(Block& b);
void addStreetTrees(Block& b, Random& random);
void addLots(Block& b, Random& random);

Block planBlock(uint64_t seed, uint64_t index)
{
    const auto [i, j] = blockCell(index);
    Block b;
    b.x = double(i) * kPitch;
    b.z = double(j) * kPitch;
    Random random = blockRandom(seed, index);
    addRoadsAndCurb(b);
    addStreetTrees(b, random);
    addLots(b, random);
    return b;
}

void addRoadsAndCurb(Block& b)
{
    const double g = kGutter;
    b.parts.push_back(Road{{b.x + g, b.z + g, b.x + kRoad - g, b.z + kPitch - g}, 15});        // along z, with the crossing
    b.parts.push_back(Road{{b.x + kRoad + g, b.z + g, b.x + kPitch - g, b.z + kRoad - g}, 13}); // along x
    b.parts.push_back(Ring{{b.x + kRoad, b.z + kRoad, b.x + kPitch, b.z + kPitch}, 0, kCurb, kSidewalk});
}

Tree planTree(double x, double z, Random& random)
{
    Tree t{x, z, random.uniform(0.15, 0.3), random.uniform(4, 6), random.uniform(1.5, 3), random.uniform(1.8, 2.8), {}};
    for (int n = 0; n < kMissingFaces; ++n) {
        uint8_t f;
        do f = uint8_t(random.next() % kCrownFaces);
        while (std::find(t.missing.begin(), t.missing.begin() + n, f) != t.missing.begin() + n);
        t.missing[n] = f;
    }
    return t;
}

/// Up to eight trees along each side of the curb, 1.5 m in from its outer edge.
void addStreetTrees(Block& b, Random& random)
{
    const double land = kPitch - kRoad, nearSide = kRoad + 1.5, farSide = kPitch - 1.5;
    for (int side = 0; side < 4; ++side)
        for (int n = 0; n < 8; ++n) {
            if (!random.chance(0.75)) continue;
            const double along = kRoad + land * (n + 0.5) / 8 + random.uniform(-1, 1);
            const double across = side % 2 ? farSide : nearSide;
            const bool alongX = side < 2;
            b.parts.push_back(planTree(b.x + (alongX ? along : across), b.z + (alongX ? across : along), random));
        }
}

/// @a n pieces of [lo, hi], each cut within a fifth of a piece of the even cut.
std::vector<double> cuts(double lo, double hi, int n, Random& random)
{
    std::vector<double> c{lo};
    const double step = (hi - lo) / n;
    for (int k = 1; k < n; ++k) c.push_back(lo + step * (k + random.uniform(-0.2, 0.2)));
    c.push_back(hi);
    return c;
}

void addLot(Block& b, Rect lot, Random& random);

/// The land inside the curb, cut into 2-4 by 2-4 lots.
void addLots(Block& b, Random& random)
{
    const double lo = kRoad + kSidewalk, hi = kPitch - kSidewalk;
    const int nx = random.between(2, 4);
    const std::vector<double> xs = cuts(lo, hi, nx, random);
    const int nz = random.between(2, 4);
    const std::vector<double> zs = cuts(lo, hi, nz, random);
    for (size_t i = 0; i + 1 < xs.size(); ++i)
        for (size_t j = 0; j + 1 < zs.size(); ++j) addLot(b, {b.x + xs[i], b.z + zs[j], b.x + xs[i + 1], b.z + zs[j + 1]}, random);
}

Building planBuilding(Rect footprint, int floors, Random& random);
Building plainBox(Rect footprint, Random& random);
void addCourtyard(Block& b, Rect footprint, Random& random);
void addPark(Block& b, Rect lot, Random& random);

/// A tower, a low building, a courtyard building, a plain box or a park.
/// (Each random number is drawn in a statement of its own: the order in
/// which a call's arguments are evaluated is unspecified.)
void addLot(Block& b, Rect lot, Random& random)
{
    const double use = random.unit();
    const double setback = random.uniform(3, 6); // beyond a street tree's crown
    const Rect footprint = lot.shrunk(setback);
    if (use < 0.35) {
        const int floors = random.between(6, 30);
        b.parts.push_back(planBuilding(footprint, floors, random));
    } else if (use < 0.60) {
        const int floors = random.between(2, 5);
        b.parts.push_back(planBuilding(footprint, floors, random));
    } else if (use < 0.75) {
        addCourtyard(b, footprint, random);
    } else if (use < 0.85) {
        b.parts.push_back(plainBox(footprint, random));
    } else {
        addPark(b, lot, random);
    }
}

/// Window columns that fit along a facade @a length long with at least
/// kPier of wall between them and at both ends.
int windowColumns(double length, double windowWidth)
{
    return std::max(0, int((length - kPier) / (windowWidth + kPier)));
}

Building planBuilding(Rect f, int floors, Random& random)
{
    Building b{f, 0, 0, floors, random.uniform(3.0, 3.6), random.uniform(1.2, 2.0), 0};
    b.columnsX = windowColumns(f.x1 - f.x0, b.windowWidth);
    b.columnsZ = windowColumns(f.z1 - f.z0, b.windowWidth);
    b.top = floors * b.floorHeight + random.uniform(0.5, 1.5); // a parapet above the top windows
    return b;
}

Building plainBox(Rect f, Random& random) { return Building{f, 0, 0, 0, 3, 1, random.uniform(5, 25)}; }

/// A closed ring with walls 0.2-0.6 m thick: one to three voxels of a large city.
void addCourtyard(Block& b, Rect f, Random& random)
{
    const double height = random.uniform(4, 12);
    const double wall = random.uniform(0.2, 0.6);
    b.parts.push_back(Ring{f, 0, height, wall});
}

/// Trees on a jittered 8 m grid inside four garden walls 0.25 m thick, with
/// gaps at the corners (walls that touch would share faces).
void addPark(Block& b, Rect lot, Random& random)
{
    const Rect w = lot.shrunk(1);
    const double t = 0.25, h = 1.2, gap = 2;
    b.parts.push_back(Slab{{w.x0 + gap, w.z0, w.x1 - gap, w.z0 + t}, 0, h});
    b.parts.push_back(Slab{{w.x0 + gap, w.z1 - t, w.x1 - gap, w.z1}, 0, h});
    b.parts.push_back(Slab{{w.x0, w.z0 + gap, w.x0 + t, w.z1 - gap}, 0, h});
    b.parts.push_back(Slab{{w.x1 - t, w.z0 + gap, w.x1, w.z1 - gap}, 0, h});
    const Rect g = lot.shrunk(4);
    const int nx = std::max(1, int((g.x1 - g.x0) / 8)), nz = std::max(1, int((g.z1 - g.z0) / 8));
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < nz; ++j) {
            if (!random.chance(0.8)) continue;
            const double dx = random.uniform(-1.5, 1.5);
            const double dz = random.uniform(-1.5, 1.5);
            const double x = g.x0 + (g.x1 - g.x0) * (i + 0.5) / nx + dx, z = g.z0 + (g.z1 - g.z0) * (j + 0.5) / nz + dz;
            b.parts.push_back(planTree(x, z, random));
        }
}

// ---------------------------------------------------------------------------
// What each part writes. sizeOf and write must agree; writeBlock checks that
// they do.

/// The stations around a building's facades: each face's corner, then the
/// two sides of each window column on it.
int ringStations(const Building& b) { return 2 * (2 * b.columnsX + 1) + 2 * (2 * b.columnsZ + 1); }

Size sizeOf(const Road& r) { return {2 * uint64_t(r.pieces + 1), 2 * uint64_t(r.pieces)}; }
Size sizeOf(const Building& b)
{
    // A lattice of stations by levels (ground, each window's bottom and top,
    // the roof), four more vertices and eight more triangles per window, and
    // a fan with a centre vertex under and over the lattice.
    const uint64_t ring = ringStations(b), levels = 2 * uint64_t(b.floors) + 2;
    const uint64_t windows = 2 * uint64_t(b.floors) * uint64_t(b.columnsX + b.columnsZ);
    return {ring * levels + 4 * windows + 2, 2 * ring * levels + 8 * windows};
}
Size sizeOf(const Slab&) { return {8, 12}; }
Size sizeOf(const Ring&) { return {16, 32}; }
Size sizeOf(const Tree&) { return {12 + 3 * (kCrownFaces - kMissingFaces), 12 + kCrownFaces - kMissingFaces}; }
Size sizeOf(const Part& part)
{
    return std::visit([](const auto& p) { return sizeOf(p); }, part);
}

/// Writes vertices and triangles into a block's slices of the mesh. Faces
/// are counter-clockwise seen from outside: closed parts come out
/// consistently oriented.
class Writer {
public:
    Writer(TriangleMesh& mesh, Size first)
        : positions_(mesh.positions.data() + first.vertices), triangles_(mesh.triangles.data() + first.triangles),
          base_(uint32_t(first.vertices))
    {
    }
    uint32_t vertex(Vec3d p)
    {
        positions_[written_.vertices] = p;
        return base_ + uint32_t(written_.vertices++);
    }
    void triangle(uint32_t a, uint32_t b, uint32_t c) { triangles_[written_.triangles++] = {a, b, c}; }
    void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d)
    {
        triangle(a, b, c);
        triangle(a, c, d);
    }
    /// The four corners of @a r at height @a y, going +x, +z, -x, -z; the first's index.
    uint32_t rectangle(Rect r, double y)
    {
        const uint32_t first = vertex({r.x0, y, r.z0});
        vertex({r.x1, y, r.z0});
        vertex({r.x1, y, r.z1});
        vertex({r.x0, y, r.z1});
        return first;
    }
    Size written() const { return written_; }

private:
    Vec3d* positions_;
    std::array<uint32_t, 3>* triangles_;
    uint32_t base_;
    Size written_;
};

double lerp(double a, double b, double t) { return a + (b - a) * t; }

void write(const Road& r, Writer& w)
{
    const Rect a = r.area;
    const bool alongZ = a.z1 - a.z0 > a.x1 - a.x0;
    uint32_t first = 0;
    for (int s = 0; s <= r.pieces; ++s) {
        const double t = double(s) / r.pieces;
        const Vec3d p = alongZ ? Vec3d{a.x0, 0, lerp(a.z0, a.z1, t)} : Vec3d{lerp(a.x0, a.x1, t), 0, a.z0};
        const Vec3d q = alongZ ? Vec3d{a.x1, 0, p.z} : Vec3d{p.x, 0, a.z1};
        const uint32_t i = w.vertex(p);
        w.vertex(q);
        if (s == 0) first = i;
    }
    for (uint32_t s = 0; s < uint32_t(r.pieces); ++s) {
        const uint32_t p0 = first + 2 * s, q0 = p0 + 1, p1 = p0 + 2, q1 = p0 + 3;
        if (alongZ) w.quad(p0, p1, q1, q0); // facing up (+y) either way
        else w.quad(p0, q0, q1, p1);
    }
}

void write(const Slab& s, Writer& w)
{
    const uint32_t b = w.rectangle(s.area, s.y0), t = w.rectangle(s.area, s.y1);
    for (uint32_t k = 0; k < 4; ++k) w.quad(b + k, t + k, t + (k + 1) % 4, b + (k + 1) % 4);
    w.quad(t, t + 3, t + 2, t + 1);
    w.quad(b, b + 1, b + 2, b + 3);
}

void write(const Ring& r, Writer& w)
{
    const Rect inner = r.outer.shrunk(r.wall);
    const uint32_t ob = w.rectangle(r.outer, r.y0), ot = w.rectangle(r.outer, r.y1);
    const uint32_t ib = w.rectangle(inner, r.y0), it = w.rectangle(inner, r.y1);
    for (uint32_t k = 0; k < 4; ++k) {
        const uint32_t n = (k + 1) % 4;
        w.quad(ob + k, ot + k, ot + n, ob + n); // outer walls
        w.quad(ib + k, ib + n, it + n, it + k); // inner walls, facing the courtyard
        w.quad(ot + k, it + k, it + n, ot + n); // top
        w.quad(ob + k, ob + n, ib + n, ib + k); // bottom
    }
}

/// A point on a building's facade ring; `window`: the segment from it to the
/// next station is a window column.
struct Station {
    double x, z;
    int face; ///< 0: z = z0, 1: x = x1, 2: z = z1, 3: x = x0
    bool window;
};

std::vector<Station> facadeStations(const Building& b)
{
    const Rect f = b.footprint;
    const double cornerX[4] = {f.x0, f.x1, f.x1, f.x0}, cornerZ[4] = {f.z0, f.z0, f.z1, f.z1};
    const double dirX[4] = {1, 0, -1, 0}, dirZ[4] = {0, 1, 0, -1};
    std::vector<Station> ring;
    ring.reserve(size_t(ringStations(b)));
    for (int face = 0; face < 4; ++face) {
        const int columns = face % 2 ? b.columnsZ : b.columnsX;
        const double length = face % 2 ? f.z1 - f.z0 : f.x1 - f.x0;
        const double pier = (length - columns * b.windowWidth) / (columns + 1);
        const auto at = [&](double s, bool window) {
            return Station{cornerX[face] + s * dirX[face], cornerZ[face] + s * dirZ[face], face, window};
        };
        ring.push_back(at(0, false));
        for (int c = 0; c < columns; ++c) {
            const double start = pier + c * (b.windowWidth + pier);
            ring.push_back(at(start, true));
            ring.push_back(at(start + b.windowWidth, false));
        }
    }
    return ring;
}

/// Ground, each floor's window bottom and top, the roof.
std::vector<double> facadeLevels(const Building& b)
{
    std::vector<double> y{0};
    for (int f = 0; f < b.floors; ++f) {
        y.push_back(f * b.floorHeight + kSill);
        y.push_back(f * b.floorHeight + kSill + kWindowHeight);
    }
    y.push_back(b.top);
    return y;
}

/// A window: the facade cell A B C D (A, B at the bottom, in ring order)
/// pushed kRecess into the building, as four sides and a back wall, whose
/// outer edges run as the flat cell's quad(A, D, C, B) would.
void writeWindow(Writer& w, const std::array<uint32_t, 4>& abcd, const std::array<Vec3d, 4>& at, Vec3d inward)
{
    const auto [A, B, C, D] = abcd;
    const uint32_t a = w.vertex(at[0] + kRecess * inward), b = w.vertex(at[1] + kRecess * inward);
    const uint32_t c = w.vertex(at[2] + kRecess * inward), d = w.vertex(at[3] + kRecess * inward);
    w.quad(A, D, d, a);
    w.quad(D, C, c, d);
    w.quad(C, B, b, c);
    w.quad(B, A, a, b);
    w.quad(a, d, c, b);
}

void write(const Building& b, Writer& w)
{
    const std::vector<Station> ring = facadeStations(b);
    const std::vector<double> y = facadeLevels(b);
    const uint32_t R = uint32_t(ring.size()), L = uint32_t(y.size());
    uint32_t first = 0;
    for (uint32_t j = 0; j < L; ++j)
        for (uint32_t i = 0; i < R; ++i) {
            const uint32_t v = w.vertex({ring[i].x, y[j], ring[i].z});
            if (i == 0 && j == 0) first = v;
        }
    const auto id = [&](uint32_t j, uint32_t i) { return first + j * R + i % R; };
    const auto position = [&](uint32_t j, uint32_t i) { return Vec3d{ring[i % R].x, y[j], ring[i % R].z}; };
    const Vec3d inward[4] = {{0, 0, 1}, {-1, 0, 0}, {0, 0, -1}, {1, 0, 0}};
    for (uint32_t j = 0; j + 1 < L; ++j)
        for (uint32_t i = 0; i < R; ++i) {
            const std::array<uint32_t, 4> cell = {id(j, i), id(j, i + 1), id(j + 1, i + 1), id(j + 1, i)};
            if (j % 2 == 1 && ring[i].window)
                writeWindow(w, cell, {position(j, i), position(j, i + 1), position(j + 1, i + 1), position(j + 1, i)},
                            inward[ring[i].face]);
            else
                w.quad(cell[0], cell[3], cell[2], cell[1]);
        }
    const Rect f = b.footprint;
    const double cx = 0.5 * (f.x0 + f.x1), cz = 0.5 * (f.z0 + f.z1);
    const uint32_t floor = w.vertex({cx, 0, cz}), roof = w.vertex({cx, b.top, cz});
    for (uint32_t i = 0; i < R; ++i) {
        w.triangle(floor, id(0, i), id(0, i + 1));
        w.triangle(roof, id(L - 1, i + 1), id(L - 1, i));
    }
}

Vec3d normalized(Vec3d v) { return (1.0 / std::sqrt(dot(v, v))) * v; }

/// The unit crown: an icosahedron (faces found as the triples of vertices
/// two apart, turned to face out) with each face cut in four, midpoints
/// pushed onto the sphere. Computed once.
const std::vector<std::array<Vec3d, 3>>& unitCrown()
{
    static const std::vector<std::array<Vec3d, 3>> crown = [] {
        const double g = (1 + std::sqrt(5.0)) / 2; // the icosahedron's vertices: (0, ±1, ±g), cycled
        std::vector<Vec3d> v;
        for (double s : {-1.0, 1.0})
            for (double t : {-g, g}) {
                v.push_back({0, s, t});
                v.push_back({s, t, 0});
                v.push_back({t, 0, s});
            }
        const auto edge = [&](size_t a, size_t b) { const Vec3d d = v[a] - v[b]; return std::abs(dot(d, d) - 4) < 1e-9; };
        std::vector<std::array<Vec3d, 3>> out;
        for (size_t a = 0; a < v.size(); ++a)
            for (size_t b = a + 1; b < v.size(); ++b)
                for (size_t c = b + 1; c < v.size(); ++c) {
                    if (!edge(a, b) || !edge(b, c) || !edge(c, a)) continue;
                    Vec3d p = normalized(v[a]), q = normalized(v[b]), r = normalized(v[c]);
                    if (dot(cross(q - p, r - p), p + q + r) < 0) std::swap(q, r);
                    const Vec3d pq = normalized(p + q), qr = normalized(q + r), rp = normalized(r + p);
                    out.push_back({p, pq, rp});
                    out.push_back({q, qr, pq});
                    out.push_back({r, rp, qr});
                    out.push_back({pq, qr, rp});
                }
        return out;
    }();
    return crown;
}

void write(const Tree& t, Writer& w)
{
    // Trunk: an open hexagonal tube, from inside the curb into the crown.
    const double h = 0.8660254037844386; // sin 60°, written out: no libm
    const double hexX[6] = {1, 0.5, -0.5, -1, -0.5, 0.5}, hexZ[6] = {0, h, h, 0, -h, -h};
    uint32_t bottom = 0;
    for (int k = 0; k < 12; ++k) {
        const uint32_t v = w.vertex({t.x + t.trunkRadius * hexX[k % 6], k < 6 ? kTrunkFoot : t.trunkTop,
                                     t.z + t.trunkRadius * hexZ[k % 6]});
        if (k == 0) bottom = v;
    }
    const uint32_t top = bottom + 6;
    for (uint32_t k = 0; k < 6; ++k) w.quad(bottom + k, top + k, top + (k + 1) % 6, bottom + (k + 1) % 6);
    // Crown: a soup around the trunk's top, a few faces missing.
    const auto& crown = unitCrown();
    for (int f = 0; f < kCrownFaces; ++f) {
        if (std::find(t.missing.begin(), t.missing.end(), f) != t.missing.end()) continue;
        std::array<uint32_t, 3> v;
        for (int c = 0; c < 3; ++c) {
            const Vec3d u = crown[size_t(f)][size_t(c)];
            v[size_t(c)] = w.vertex({t.x + t.crownRadius * u.x, t.trunkTop + t.crownHeight * u.y, t.z + t.crownRadius * u.z});
        }
        w.triangle(v[0], v[1], v[2]);
    }
}

void writeBlock(const Block& block, TriangleMesh& mesh)
{
    Writer w(mesh, block.first);
    for (const Part& p : block.parts) std::visit([&](const auto& q) { write(q, w); }, p);
    if (!(w.written() == block.size))
        throw std::logic_error("cityScene: a part wrote other counts than its plan said"); // a bug here, never input
}

} // namespace
} // namespace svo
