// NanoVDB grids built on the GPU (svo/gl/nano_grid_builder.h): the passes
// run in order, the host reads back twice (the node counts, to size the
// grid; the upper nodes' statistics, for the headers) and writes the headers.
#include "svo/gl/nano_grid_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>

#include "nano_header.h"
#include "nano_layout.h"
#include "nanovdb_shaders.h"
#include "svo/core/error.h"
#include "svo/gl/fill_words.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"

namespace svo::gl {
namespace {

void passBarrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); }

uint32_t leafWords(NanoKind kind)
{
    switch (kind) {
    case NanoKind::Mask: return gpu::kNanoLeafWordsMask;
    case NanoKind::Bool: return gpu::kNanoLeafWordsBool;
    case NanoKind::Vec3f: return gpu::kNanoLeafWordsVec3f;
    default: return gpu::kNanoLeafWordsValue;
    }
}

/// Words per value, and the internal nodes' and the root's sizes, by kind (nano_layout.h).
uint32_t valueWords(NanoKind kind) { return kind == NanoKind::Vec3f ? 3 : 1; }
uint32_t lowerWords(NanoKind kind) { return kind == NanoKind::Vec3f ? gpu::kNanoLowerWordsVec3f : gpu::kNanoLowerWords; }
uint32_t upperWords(NanoKind kind) { return kind == NanoKind::Vec3f ? gpu::kNanoUpperWordsVec3f : gpu::kNanoUpperWords; }
uint32_t rootBytes(NanoKind kind) { return kind == NanoKind::Vec3f ? gpu::kNanoRootBytesVec3f : gpu::kNanoRootBytes; }

/// The leaves' buffers on the device: the caller's, or uploads of the host
/// arrays; the tiles' upload.
struct DeviceLeaves {
    const Buffer* origins = nullptr;
    const Buffer* masks = nullptr;
    const Buffer* values = nullptr; // null: no values
    const Buffer* tiles = nullptr;  // null: no tiles
};

void checkLeaves(NanoKind kind, const NanoLeaves& in, const NanoGridHeader& header)
{
    if (header.name.size() >= 256)
        throw InvalidInput(fmt::format("NanoVDB GPU build: grid name of {} bytes; NanoVDB holds at most 255", header.name.size()));
    if (in.tileCount && !in.tiles) throw InvalidInput("NanoVDB GPU build: a tile count without tiles");
    if (kind == NanoKind::Vec3f && (in.tileCount || in.activeWord))
        throw InvalidInput("NanoVDB GPU build: Vec3f grids take neither tiles nor an active word");
    if (header.signedFloodFill && kind != NanoKind::Float)
        throw InvalidInput("NanoVDB GPU build: a signed flood fill is for Float level sets");
    if (!in.count) return;
    if (in.origins) {
        if (!in.masks) throw InvalidInput("NanoVDB GPU build: leaf origins without masks");
        return;
    }
    if (!in.originBuffer || !in.maskBuffer) throw InvalidInput("NanoVDB GPU build: no leaf origins or masks given");
    const uint64_t n = in.count;
    if (in.originBuffer->bytes() < 12 * n || in.maskBuffer->bytes() < 64 * n ||
        (in.valueBuffer && in.valueBuffer->bytes() < 2048 * valueWords(kind) * n))
        throw InvalidInput(fmt::format("NanoVDB GPU build: device buffers too small for {} leaves", n));
}

DeviceLeaves deviceLeaves(const Context& context, NanoKind kind, const NanoLeaves& in)
{
    static_assert(sizeof(NanoTile) == 4 * gpu::kNanoTileWords, "a tile as nano_layout.h reads it");
    const Buffer* tiles = nullptr;
    if (in.tileCount) {
        tiles = &context.scratch("nanovdb tiles", sizeof(NanoTile) * uint64_t(in.tileCount));
        tiles->write(0, sizeof(NanoTile) * uint64_t(in.tileCount), in.tiles);
    }
    if (!in.origins) return {in.originBuffer, in.maskBuffer, in.valueBuffer, tiles};
    const uint64_t n = in.count;
    DeviceLeaves d;
    d.tiles = tiles;
    if (!n) return d;
    d.origins = &context.scratch("nanovdb leaf origins", 12 * n);
    d.masks = &context.scratch("nanovdb leaf masks", 64 * n);
    d.origins->write(0, 12 * n, in.origins);
    d.masks->write(0, 64 * n, in.masks);
    if (in.values) {
        const uint64_t bytes = 2048 * valueWords(kind) * n;
        d.values = &context.scratch("nanovdb leaf values", bytes);
        d.values->write(0, bytes, in.values);
    }
    return d;
}

/// The origin of input entry @a i (leaves, then tiles), for messages.
std::array<int32_t, 3> originOf(const NanoLeaves& in, const DeviceLeaves& d, uint32_t i)
{
    std::array<int32_t, 3> o{};
    if (i >= in.count) return in.tiles[i - in.count].origin;
    if (in.origins) return in.origins[i];
    d.origins->read(12 * uint64_t(i), 12, o.data());
    return o;
}

/// Scratch buffers of one build, bound to their slots.
struct Scratch {
    const Buffer* sort;
    const Buffer* ranks;
    const Buffer* stats;
    const Buffer* counters;
    const Buffer* scan;
};

/// @a n real entries (leaves and tiles), @a entries the sort's power of two.
Scratch bindScratch(const Context& context, const DeviceLeaves& d, uint64_t n, uint64_t entries)
{
    Scratch s;
    s.sort = &context.scratch("nanovdb sort", entries * gpu::kNanoSortWords * 4);
    s.ranks = &context.scratch("nanovdb ranks", (6 * n + 2) * 4); // nano_common.glsl's tables
    s.stats = &context.scratch("nanovdb stats", 3 * n * gpu::kNanoStatWords * 4);
    s.counters = &context.scratch("nanovdb counters", gpu::kNanoCountWords * 4);
    s.scan = &context.scratch("nanovdb scan chunks", ((n + gpu::kNanoScanChunk - 1) / gpu::kNanoScanChunk) * 12 + 12);
    s.counters->clearUint(0, gpu::kNanoCountWords * 4);
    // Slots a build without leaves or without tiles leaves unread are bound to the sort's buffer.
    (d.origins ? d.origins : s.sort)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_ORIGINS);
    (d.masks ? d.masks : s.sort)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_MASKS);
    (d.values ? d.values : s.sort)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_VALUES);
    (d.tiles ? d.tiles : s.sort)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_TILES);
    s.sort->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_SORT);
    s.ranks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_RANKS);
    s.stats->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_STATS);
    s.counters->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_COUNTERS);
    s.scan->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_SCAN);
    return s;
}

/// With SVO_NANO_PASS_MS set, each phase of a build waited for (glFinish)
/// and its milliseconds printed to stderr: where a build's time goes, for
/// the benchmarks (bench/gpu_host_issue45.sh); off, it costs nothing.
struct PhaseClock {
    const bool on = std::getenv("SVO_NANO_PASS_MS") != nullptr;
    std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
    std::string line;
    void operator()(const char* phase)
    {
        if (!on) return;
        glFinish();
        const auto now = std::chrono::steady_clock::now();
        line += fmt::format(" {} {:.3f}", phase, std::chrono::duration<double, std::milli>(now - t).count());
        t = now;
    }
    ~PhaseClock()
    {
        if (on) fmt::print(stderr, "nanovdb build ms:{}\n", line);
    }
};

/// Passes 1 to 3: sort entries, the bitonic sort, the node ranks and counts.
/// The sort's steps within blocks of 1024 entries run in shared memory
/// (nano_sort_local.comp), a dispatch for all of them; only the longer
/// distances take a dispatch a step (nano_sort.comp): 36 dispatches instead
/// of 153 for 2^17 entries.
void sortAndRank(const Context& context, uint32_t leaves, uint32_t n, uint32_t entries, PhaseClock& phase)
{
    const Program& keys = context.program(nanovdbShaders(), {"nano_keys.comp"});
    keys.set("uLeafCount", leaves);
    keys.set("uEntryCount", n);
    keys.set("uEntries", entries);
    keys.dispatchRows((entries + 255) / 256);
    passBarrier();
    phase("keys");
    const uint32_t block = std::min<uint32_t>(entries, 1024);
    const Program& local = context.program(nanovdbShaders(), {"nano_sort_local.comp"});
    local.set("uBlock", block);
    const Program& sort = context.program(nanovdbShaders(), {"nano_sort.comp"});
    sort.set("uEntries", entries);
    local.set("uK", 0u);
    local.dispatchRows(entries / block);
    passBarrier();
    for (uint32_t k = block << 1; k <= entries; k <<= 1) {
        for (uint32_t j = k >> 1; j >= block; j >>= 1) {
            sort.set("uK", k);
            sort.set("uJ", j);
            sort.dispatchRows((entries + 255) / 256);
            passBarrier();
        }
        local.set("uK", k);
        local.dispatchRows(entries / block);
        passBarrier();
    }
    phase("sort");
    const Program& scan = context.program(nanovdbShaders(), {"nano_scan.comp"});
    scan.set("uLeafCount", leaves);
    scan.set("uEntryCount", n);
    const uint64_t chunks = (uint64_t(n) + gpu::kNanoScanChunk - 1) / gpu::kNanoScanChunk;
    for (const uint32_t phase : {0u, 1u, 2u}) { // count each chunk's starts, sum the chunks, rank the entries
        scan.set("uPhase", phase);
        if (phase == 1) scan.dispatch(1);
        else scan.dispatchRows(chunks);
        passBarrier();
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

/// Passes 4 to 6: leaves (and their values), lower nodes, upper nodes, of
/// @a entries leaves and tiles.
void fillNodes(const Context& context, NanoKind kind, const NanoTreeFacts& f, uint32_t entries, bool hasValues,
               uint32_t background, const std::optional<uint32_t>& active, PhaseClock& phase)
{
    const uint32_t n = f.nodes[0];
    const Program& leaves = context.program(nanovdbShaders(), {"nano_leaves.comp"});
    const Program& values = context.program(nanovdbShaders(), {"nano_values.comp"});
    for (const Program* p : {&leaves, &values}) {
        p->set("uLeafCount", n);
        p->set("uEntryCount", entries);
        p->set("uType", uint32_t(kind));
        p->set("uLeafAt", uint32_t(f.at[0] / 4));
        p->set("uLeafWords", leafWords(kind));
        p->set("uHasValues", hasValues ? 1u : 0u);
        p->set("uBackground", background);
        p->set("uHasActive", active && !hasValues ? 1u : 0u);
        p->set("uActive", active.value_or(background));
    }
    leaves.dispatchRows(n); // a group a leaf (none for a grid of tiles alone)
    if (kind != NanoKind::Mask) values.dispatchRows((16 * uint64_t(n) + 255) / 256); // masks hold no values
    passBarrier();
    phase("leaves");
    const Program& internal = context.program(nanovdbShaders(), {"nano_internal.comp"});
    internal.set("uLeafCount", n);
    internal.set("uEntryCount", entries);
    internal.set("uType", uint32_t(kind));
    internal.set("uBackground", background);
    internal.set("uRootAt", uint32_t(f.at[3] / 4));
    for (uint32_t upper = 0; upper < 2; ++upper) {
        internal.set("uUpper", upper);
        internal.set("uNodeCount", f.nodes[1 + upper]);
        internal.set("uNodeAt", uint32_t(f.at[1 + upper] / 4));
        internal.set("uChildAt", uint32_t(f.at[upper] / 4));
        internal.set("uChildWords", upper ? lowerWords(kind) : leafWords(kind));
        internal.set("uStatsAt", upper ? n + f.nodes[1] : n);
        internal.set("uChildStatsAt", upper ? n : 0u);
        internal.dispatchRows(f.nodes[1 + upper]);
        passBarrier();
        phase(upper ? "uppers" : "lowers");
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

/// Byte offsets of each level, breadth-first after the headers, as the CPU builder places them.
void layOut(NanoTreeFacts& f, NanoKind kind)
{
    const uint64_t rootAt = gpu::kNanoGridBytes + gpu::kNanoTreeBytes;
    const uint64_t upperAt = rootAt + rootBytes(kind) + uint64_t(gpu::kNanoTileBytes) * f.nodes[2];
    const uint64_t lowerAt = upperAt + uint64_t(upperWords(kind)) * 4 * f.nodes[2];
    const uint64_t leafAt = lowerAt + uint64_t(lowerWords(kind)) * 4 * f.nodes[1];
    f.at = {leafAt, lowerAt, upperAt, rootAt};
    f.gridBytes = leafAt + uint64_t(leafWords(kind)) * 4 * f.nodes[0];
    if (f.gridBytes / 4 >= (uint64_t(1) << 32))
        throw Unsupported(fmt::format("NanoVDB GPU build: a grid of {} bytes is beyond 32-bit word addressing", f.gridBytes));
}

/// A hardware driver's storage-block limit is real: past it, writes are lost without an error.
void checkBufferLimit(const Context& context, NanoKind kind, uint64_t gridBytes, uint64_t leaves)
{
    const uint64_t limit = context.shaderBufferLimit();
    const uint64_t largest = std::max(gridBytes, 2048 * valueWords(kind) * leaves);
    if (limit && largest > limit)
        throw Unsupported(fmt::format("NanoVDB GPU build: a buffer of {} bytes exceeds the driver's shader storage limit of {}",
                                      largest, limit));
}

float floatOf(uint32_t w)
{
    float x;
    std::memcpy(&x, &w, 4);
    return x;
}

/// nanovdb::Vec3f::lengthSqr of three float words (nano_stats.glsl's, unfused).
float lengthSqr(const std::array<uint32_t, 3>& v)
{
    const float x = floatOf(v[0]), y = floatOf(v[1]), z = floatOf(v[2]);
    const float xx = x * x, yy = y * y, zz = z * z;
    const float xy = xx + yy;
    return xy + zz;
}

/// The root's statistics: the upper nodes' merged in order, as the CPU builder folds them.
void foldUppers(NanoTreeFacts& f, NanoKind kind, const std::vector<uint32_t>& stats)
{
    using Value = std::array<uint32_t, 3>;
    auto less = [kind](const Value& a, const Value& b) {
        if (kind == NanoKind::Vec3f) return lengthSqr(a) < lengthSqr(b);
        if (kind != NanoKind::Float) return int32_t(a[0]) < int32_t(b[0]);
        return floatOf(a[0]) < floatOf(b[0]);
    };
    for (uint32_t u = 0; u < f.nodes[2]; ++u) {
        const uint32_t* s = stats.data() + size_t(u) * gpu::kNanoStatWords;
        if (int32_t(s[0]) > int32_t(s[3])) continue; // nothing active
        const Value mn{s[6], s[7], s[8]}, mx{s[9], s[10], s[11]};
        if (!f.any) {
            f.any = true;
            for (size_t i = 0; i < 6; ++i) f.bbox[i] = int32_t(s[i]);
            f.minimum = mn, f.maximum = mx;
            continue;
        }
        for (size_t i = 0; i < 3; ++i) {
            f.bbox[i] = std::min(f.bbox[i], int32_t(s[i]));
            f.bbox[3 + i] = std::max(f.bbox[3 + i], int32_t(s[3 + i]));
        }
        if (less(mn, f.minimum)) f.minimum = mn;
        if (less(f.maximum, mx)) f.maximum = mx;
    }
}

/// a·b mod CRC-32's polynomial, both reflected (bit 31 is x^0), as nano_crc.comp's mulMod.
uint32_t crcMulMod(uint32_t a, uint32_t b)
{
    uint32_t p = 0;
    for (int i = 31; i >= 0; --i) {
        if ((a >> i) & 1u) p ^= b;
        b = (b >> 1) ^ ((b & 1u) ? 0xEDB88320u : 0u);
    }
    return p;
}

/// x^(8·n) mod P: the CRC register's shift past n zero bytes.
uint32_t crcShift(uint64_t n)
{
    uint32_t r = 0x80000000u, x = 0x00800000u; // 1; x^8 (a byte)
    for (; n; n >>= 1, x = crcMulMod(x, x))
        if (n & 1) r = crcMulMod(r, x);
    return r;
}

/// nano_crc.comp's shifts of a block's @a pieces pieces of @a pieceBytes each to its end (64 values).
std::vector<uint32_t> crcShiftsToEnd(uint32_t pieces, uint64_t pieceBytes)
{
    std::vector<uint32_t> shifts(64, 0);
    for (uint32_t t = 0; t < pieces; ++t) shifts[t] = crcShift(pieceBytes * (pieces - 1 - t));
    return shifts;
}

/// CRC-32's byte table (reflected 0xEDB88320), for nano_crc.comp.
std::vector<uint32_t> crcTable()
{
    std::vector<uint32_t> table(256);
    for (uint32_t e = 0; e < 256; ++e) {
        uint32_t c = e;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[e] = c;
    }
    return table;
}

/// How nano_crc.comp cuts a node of @a words: blocks of @a pieces slices of
/// @a slice words (odd, against shared-memory bank conflicts; at most 33, as
/// few blocks as that allows; at least 16 words where the node has them, so
/// that a slice's table CRC outweighs its shift); @a blocks[k] registers per
/// node after dispatch k (the last is 1; further dispatches take 64 pieces).
struct CrcPlan {
    uint32_t pieces = 64;
    uint32_t slice = 1;
    std::vector<uint32_t> blocks;
};

CrcPlan crcPlan(uint32_t words)
{
    CrcPlan plan;
    while (plan.pieces > 1 && plan.pieces * 16 > words) plan.pieces >>= 1;
    uint32_t per = (words + plan.pieces * 33 - 1) / (plan.pieces * 33);
    plan.slice = (words + plan.pieces * per - 1) / (plan.pieces * per);
    plan.slice |= 1;
    plan.blocks.push_back(per);
    while (per > 1) plan.blocks.push_back(per = (per + 63) / 64);
    return plan;
}

/// The most loop iterations one nano_crc.comp invocation takes (the table
/// 4, a slice twice 33, the shift 32, the xors 7 + 7: 116).
constexpr uint64_t kCrcLoopIterations = 128;

/// NanoVDB's full checksum of the grid in @a grid: the CRC-32 of the
/// headers and the root's tiles past the checksum field (the host's
/// @a head, the tiles read back), and the CRC-32 of the nodes' CRC-32s
/// (upper, lower, leaf nodes in buffer order, from nano_crc.comp, each held
/// in a std::uint_fast32_t as nanovdb::GridChecksum holds it); written into
/// the grid and into @a head.
void checksumOnGpu(const Context& context, NanoKind kind, const NanoTreeFacts& f, const Buffer& stats,
                   const Buffer& grid, std::vector<uint8_t>& head)
{
    const uint64_t loopLimit = context.info().loopLimit;
    if (loopLimit && loopLimit < kCrcLoopIterations)
        throw Unsupported(fmt::format("NanoVDB GPU checksum: the driver's loop limit of {} is under the {} iterations it needs",
                                      loopLimit, kCrcLoopIterations));
    const Program& crc = context.program(nanovdbShaders(), {"nano_crc.comp"});
    auto wordsOf = [&](size_t level) {
        return level == 2 ? upperWords(kind) : level == 1 ? lowerWords(kind) : leafWords(kind);
    };
    uint64_t regWords = 256; // the table, then the most registers a level's folds keep
    for (size_t level = 0; level < 3; ++level) {
        const CrcPlan plan = crcPlan(wordsOf(level));
        uint64_t sum = 256;
        for (size_t k = 0; k + 1 < plan.blocks.size(); ++k) sum += uint64_t(f.nodes[level]) * plan.blocks[k];
        regWords = std::max(regWords, sum);
    }
    const Buffer& regs = context.scratch("nanovdb crc registers", regWords * 4);
    regs.write(0, 256 * 4, crcTable().data());
    regs.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_SORT);
    uint32_t sumAt = 0;
    for (int level = 2; level >= 0; --level) {
        const uint32_t count = f.nodes[size_t(level)];
        const uint32_t words = wordsOf(size_t(level));
        const CrcPlan plan = crcPlan(words);
        crc.set("uNodeCount", count);
        crc.set("uNodeAt", uint32_t(f.at[size_t(level)] / 4));
        crc.set("uNodeWords", words);
        crc.set("uSliceWords", plan.slice);
        uint64_t pieceBytes = 4 * plan.slice;
        uint32_t inAt = 0, outAt = 256;
        for (size_t k = 0; k < plan.blocks.size(); ++k) {
            const bool last = k + 1 == plan.blocks.size();
            const uint32_t pieces = k == 0 ? plan.pieces : 64;
            crc.set("uPieces", pieces);
            crc.set("uShiftBy", crcShiftsToEnd(pieces, pieceBytes));
            crc.set("uFromGrid", k == 0 ? 1u : 0u);
            crc.set("uInAt", inAt);
            crc.set("uInPer", k == 0 ? 0u : plan.blocks[k - 1]);
            crc.set("uOutPer", plan.blocks[k]);
            crc.set("uOutAt", last ? sumAt : outAt);
            crc.set("uLast", last ? 1u : 0u);
            const uint64_t blocks = uint64_t(count) * plan.blocks[k];
            crc.dispatchRows((blocks * pieces + 63) / 64);
            passBarrier();
            inAt = outAt;
            outAt += uint32_t(blocks);
            pieceBytes *= pieces;
        }
        sumAt += count;
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<uint32_t> nodeCrcs(sumAt);
    stats.readBulk(0, uint64_t(sumAt) * 4, nodeCrcs.data());
    const uint64_t tilesAt = head.size(), rootEnd = f.at[2];
    std::vector<uint8_t> tiles(rootEnd - tilesAt);
    grid.read(tilesAt, tiles.size(), tiles.data());
    const uint32_t headCrc = crc32Of(tiles.data(), tiles.size(), crc32Of(head.data() + 16, head.size() - 16));
    const std::vector<std::uint_fast32_t> sums(nodeCrcs.begin(), nodeCrcs.end());
    const uint64_t checksum = uint64_t(crc32Of(sums.data(), sums.size() * sizeof(std::uint_fast32_t))) << 32 | headCrc;
    std::memcpy(head.data() + 8, &checksum, 8);
    grid.write(8, 8, &checksum);
}

/// The most loop iterations one nano_flood.comp invocation takes: an upper
/// node's mask scan (1024 words) and its 32 + 32² + 32³ entries.
constexpr uint64_t kFloodLoopIterations = 1024 + 32 + 32 * 32 + 32 * 32 * 32;

/// OpenVDB's signed flood fill of a level set's inactive values, on the
/// grid: leaves, then lower, then upper nodes, an invocation a node
/// (nano_flood.comp).
void floodOnGpu(const Context& context, const NanoTreeFacts& f, double background)
{
    const uint64_t loopLimit = context.info().loopLimit;
    if (loopLimit && loopLimit < kFloodLoopIterations)
        throw Unsupported(fmt::format("NanoVDB GPU flood fill: the driver's loop limit of {} is under the {} "
                                      "iterations it needs",
                                      loopLimit, kFloodLoopIterations));
    const Program& flood = context.program(nanovdbShaders(), {"nano_flood.comp"});
    const float outside = std::abs(float(background)), minus = -outside;
    uint32_t word = 0;
    std::memcpy(&word, &outside, 4);
    flood.set("uOutside", word);
    std::memcpy(&word, &minus, 4);
    flood.set("uMinus", word);
    for (uint32_t level = 0; level < 3; ++level) { // bottom up: a node reads its children's filled values
        if (!f.nodes[level]) continue;
        flood.set("uLevel", level);
        flood.set("uNodeAt", uint32_t(f.at[level] / 4));
        flood.set("uNodeCount", f.nodes[level]);
        flood.dispatchRows((uint64_t(f.nodes[level]) + 63) / 64);
        passBarrier();
    }
}

void throwOnBadLeaves(const NanoLeaves& in, const DeviceLeaves& d, const uint32_t* counters)
{
    auto what = [&](uint32_t i) { return i < in.count ? "leaf" : "tile"; };
    if (uint32_t bad = counters[gpu::kNanoCountMisaligned]) {
        const auto o = originOf(in, d, bad - 1);
        throw InvalidInput(fmt::format("NanoVDB GPU build: {} origin ({}, {}, {}) is not a multiple of 8", what(bad - 1),
                                       o[0], o[1], o[2]));
    }
    if (uint32_t twice = counters[gpu::kNanoCountRepeated]) { // the later of two equal keys: a tile when one is
        const auto o = originOf(in, d, twice - 1);
        throw InvalidInput(fmt::format("NanoVDB GPU build: {} ({}, {}, {}) given twice, or on a leaf", what(twice - 1), o[0],
                                       o[1], o[2]));
    }
}

/// The grid of leaves and tiles (some): sort, rank, size, fill, then the headers.
NanoGridBuffer buildFromLeaves(const Context& context, NanoKind kind, const NanoLeaves& in, const NanoGridHeader& header,
                               bool hostCopy)
{
    PhaseClock phase;
    phase("start");
    NanoTreeFacts f;
    f.nodes[0] = in.count;
    const DeviceLeaves d = deviceLeaves(context, kind, in);
    const uint32_t n = in.count + in.tileCount;
    uint32_t entries = 1;
    while (entries < n) entries <<= 1;
    const Scratch s = bindScratch(context, d, n, entries);
    phase("upload");
    sortAndRank(context, in.count, n, entries, phase);
    phase("scan");
    uint32_t counters[gpu::kNanoCountWords] = {};
    s.counters->read(0, sizeof counters, counters);
    checkGl("NanoVDB GPU build: sort and rank");
    throwOnBadLeaves(in, d, counters);
    f.nodes[1] = counters[gpu::kNanoCountLower];
    f.nodes[2] = counters[gpu::kNanoCountUpper];
    layOut(f, kind);
    checkBufferLimit(context, kind, f.gridBytes, in.count);
    NanoGridBuffer out{context.lendScratch(kNanoGridScratch, f.gridBytes), f.gridBytes, f.nodes, {}};
    fillWords(context, out.grid, 0, f.gridBytes); // not a clear: see fill_words.h
    phase("size+zero");
    out.grid.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NANO_GRID);
    fillNodes(context, kind, f, n, d.values != nullptr, backgroundWord(kind, header.background), in.activeWord, phase);
    if (header.signedFloodFill) floodOnGpu(context, f, header.background);
    std::vector<uint32_t> upperStats(size_t(f.nodes[2]) * gpu::kNanoStatWords);
    s.stats->read(uint64_t(f.nodes[0] + f.nodes[1]) * gpu::kNanoStatWords * 4, upperStats.size() * 4, upperStats.data());
    s.counters->read(0, sizeof counters, counters);
    checkGl("NanoVDB GPU build: nodes");
    f.voxels = uint64_t(counters[gpu::kNanoCountVoxelsHigh]) << 32 | counters[gpu::kNanoCountVoxelsLow];
    f.activeTiles = counters[gpu::kNanoCountActiveTiles];
    foldUppers(f, kind, upperStats);
    std::vector<uint8_t> head = nanoHeader(kind, header, f);
    out.grid.write(0, head.size(), head.data());
    phase("headers");
    if (header.checksum) checksumOnGpu(context, kind, f, *s.stats, out.grid, head);
    phase("checksum");
    if (hostCopy) {
        out.host.resize(f.gridBytes);
        out.grid.readBulk(0, f.gridBytes, out.host.data());
    }
    checkGl("NanoVDB GPU build: headers");
    return out;
}

/// The grid of no leaves: its headers alone.
NanoGridBuffer emptyGrid(NanoKind kind, const NanoGridHeader& header, bool hostCopy)
{
    NanoTreeFacts f;
    layOut(f, kind);
    const std::vector<uint8_t> head = nanoHeader(kind, header, f);
    NanoGridBuffer out{Buffer("NanoVDB grid", f.gridBytes, head.data()), f.gridBytes, f.nodes, {}};
    if (hostCopy) out.host = head;
    checkGl("NanoVDB GPU build: empty grid");
    return out;
}

} // namespace

NanoGridBuffer buildNanoGridGpu(const Context& context, NanoKind kind, const NanoLeaves& in, const NanoGridHeader& header,
                                bool hostCopy)
{
    checkLeaves(kind, in, header);
    const uint64_t entries = uint64_t(in.count) + in.tileCount;
    if (entries > (1u << 26)) // the sort's entries and the stats' words stay within 32 bits
        throw Unsupported(fmt::format("NanoVDB GPU build: {} leaves and tiles exceed one build (at most 2^26)", entries));
    const Context::Scope scope(context);
    return entries ? buildFromLeaves(context, kind, in, header, hostCopy) : emptyGrid(kind, header, hostCopy);
}

} // namespace svo::gl
