// The GPU passes of winding_number.h: the tree's upload and the two
// evaluations, cut into dispatches so that a long one can be interrupted.
#include "svo/gl/winding_number.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "svo/core/region.h"
#include "svo/gl/buffer.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/gl/timer_query.h"
#include "svo/gl/wait_for_gpu.h"
#include "svo/core/error.h"
#include "field_layout.h"
#include "fields_shaders.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

} // namespace

WindingResult computeWinding(Context& context, const GridSpec& grid, const WindingTree& tree, const WindingRequest& request, RunStats* report)
{
    if (!(request.beta > 0)) throw InvalidInput(fmt::format("a winding accuracy (beta) of {}: it must be positive", request.beta));
    if (tree.depth + 1 > gpu::kWindingStack)
        throw Unsupported(fmt::format("a winding tree {} levels deep is more than the shader's stack holds ({})",
                                      tree.depth + 1, gpu::kWindingStack));
    WindingResult result;
    RunStats stats;
    const BrickBox box = request.brickBox ? withinGrid(grid, *request.brickBox) : bricksMeeting(grid, std::nullopt);
    for (int a = 0; a < 3; ++a) result.brickOrigin[a] = box.lo[a], result.brickDims[a] = box.hi[a] - box.lo[a];
    const uint64_t boxBricks = uint64_t(result.brickDims[0]) * result.brickDims[1] * result.brickDims[2];
    if (request.perBrick && boxBricks > (uint64_t(1) << 31))
        throw Unsupported(fmt::format("the grid's box holds {} bricks, more than the winding pass evaluates (2^31); use a "
                                      "coarser grid",
                                      boxBricks));
    const uint64_t nb = request.bricks.size();
    const Context::Scope scope(context);
    request.checkpoint(0.0, "winding upload");

    auto t0 = Clock::now();
    std::vector<uint32_t> brickWords(std::max<uint64_t>(nb, 1) * 3, 0);
    for (uint64_t i = 0; i < nb; ++i)
        for (int a = 0; a < 3; ++a) brickWords[3 * i + a] = request.bricks[i][a];
    TimerQuery uploadTimer;
    uploadTimer.begin();
    const Buffer positions("winding positions", tree.positions.size() * sizeof(Vec3d), tree.positions.data());
    const Buffer indices("winding indices", tree.triangles.size() * 12, tree.triangles.data());
    const Buffer nodes("winding nodes", tree.nodes.size() * 4, tree.nodes.data());
    const Buffer links("winding links", tree.links.size() * 4, tree.links.data());
    const Buffer order("winding order", tree.order.size() * 4, tree.order.data());
    const Buffer bricks("winding bricks", brickWords.size() * 4, brickWords.data());
    // The results, then one word a walk sets when it stopped at the driver's loop limit.
    const uint64_t resultBytes = std::max<uint64_t>(std::max(nb * sizeof(Brick), request.perBrick ? boxBricks * 4 : 0), 4);
    const uint64_t outBytes = resultBytes + 4;
    // One shader buffer holds each array (Context::shaderBufferLimit): refused,
    // never cut short. The box's brick centres shrink with a region, as the
    // band's bricks do (a BufferLimit, which the front door answers with regions).
    const uint64_t block = context.shaderBufferLimit();
    if (block && request.perBrick && boxBricks * 4 + 4 > block)
        throw DeviceError(fmt::format("winding numbers at the grid's {} brick centres need {} bytes in one GPU buffer, "
                                      "more than the {} a shader addresses; use a coarser grid",
                                      boxBricks, boxBricks * 4 + 4, block));
    if (block && std::max(outBytes, brickWords.size() * 4) > block)
        throw BufferLimit(fmt::format("winding numbers for {} bricks need {} bytes in one GPU buffer, more than the {} a "
                                      "shader addresses; use a coarser grid",
                                      nb, std::max(outBytes, brickWords.size() * 4), block));
    const Buffer& out = context.scratch("winding output", outBytes);
    uploadTimer.end();
    checkGl("winding upload");
    stats.stages.push_back({"winding upload", -1, msSince(t0)});
    positions.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_POSITIONS);
    indices.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_INDICES);
    nodes.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_WINDING_NODES);
    links.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_WINDING_LINKS);
    order.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_WINDING_ORDER);
    bricks.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_WINDING_BRICKS);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_WINDING_OUT);
    stats.gpuBytes = positions.bytes() + indices.bytes() + nodes.bytes() + links.bytes() + order.bytes() +
                     bricks.bytes() + outBytes;

    // The per-brick mode is winding_number.comp's; the per-voxel mode is
    // cut as WindingWork says. On an H100 the column walk was 1.5-1.9x
    // slower (bench/results/nvidia-h100/winding_column.md), on llvmpipe
    // 2.4x faster.
    const bool columns =
        request.work == WindingWork::Columns || (request.work == WindingWork::Auto && context.info().software);
    const Program& pointProgram = context.program(fieldsShaders(), {"winding_number.comp"});
    const Program& voxelProgram = columns ? context.program(fieldsShaders(), {"winding_columns.comp"}) : pointProgram;
    // beta^2 in float; +infinity as the largest float, which no squared
    // distance exceeds.
    const double beta2 = request.beta * request.beta;
    // Where the driver ends loops silently, a walk stops short of it and says
    // so. The walks of one SIMD vector's lanes diverge, so each lane gets its
    // share of the limit; 64 iterations are the loops around the walks.
    const uint64_t loopLimit = context.info().loopLimit;
    for (const Program* program : {&pointProgram, &voxelProgram}) {
        program->set("uBeta2", beta2 < 3.0e38 ? float(beta2) : 3.0e38f);
        program->set("uStepBudget",
                      loopLimit ? uint32_t((loopLimit - 64) / context.info().loopLanes) : 0xFFFFFFFFu);
        program->set("uFlagWord", uint32_t(resultBytes / 4));
    }
    const uint32_t zero = 0;
    out.write(resultBytes, 4, &zero);
    // Dispatches of a bounded size: the checkpoint runs between them.
    auto run = [&](const char* name, const Program& program, uint32_t mode, uint64_t count, uint64_t perDispatch,
                   uint64_t threadsPerUnit, double from, double to) {
        const auto w0 = Clock::now();
        TimerQuery timer;
        timer.begin();
        if (&program == &pointProgram) { // winding_columns.comp has the per-voxel mode only
            program.set("uMode", mode);
            program.set("uBricks", result.brickDims[0], result.brickDims[1], result.brickDims[2]);
            program.set("uBrickOrigin", result.brickOrigin[0], result.brickOrigin[1], result.brickOrigin[2]);
        }
        for (uint64_t first = 0; first < count; first += perDispatch) {
            const uint64_t last = std::min(count, first + perDispatch);
            program.set("uFirst", uint32_t(first));
            program.set("uCount", uint32_t(last));
            // As many workgroups as units, even on llvmpipe: with 256 groups
            // each looping over ~44 bricks of the per-voxel mode, llvmpipe
            // (Mesa 22.3) left inside voxels unset past the 7,000th brick
            // (a closed icosphere's winding solid at 240³ lost 5 % of its
            // voxels), while one unit per group is exact there as on NVIDIA.
            const uint64_t groups = std::min<uint64_t>((last - first) * threadsPerUnit / 64 + 1, 65535);
            program.dispatch(uint32_t(groups));
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
            checkGl(name);
            waitForGpu([&] { request.checkpoint(from + (to - from) * double(first) / double(count), name); });
        }
        timer.end();
        checkGl(name);
        waitForGpu([] {});
        uint32_t stopped = 0;
        out.read(resultBytes, 4, &stopped);
        if (stopped)
            throw DeviceError(fmt::format("winding numbers: {} ends a shader's loops after {} iterations, and walking this "
                                          "mesh's winding tree at accuracy {} takes more; use a smaller winding accuracy "
                                          "(1.5 by default) or a hardware GPU",
                                          context.info().renderer, loopLimit, request.beta));
        stats.stages.push_back({name, timer.milliseconds(), msSince(w0)});
    };
    if (request.perBrick) {
        run("winding per brick", pointProgram, 1, boxBricks, uint64_t(1) << 20, 1, 0.05, 0.45);
        result.perBrick.resize(boxBricks);
        out.readBulk(0, boxBricks * 4, result.perBrick.data());
    }
    if (nb) {
        out.clearUint(0, nb * sizeof(Brick));
        run("winding per voxel", voxelProgram, 0, nb, uint64_t(1) << 14, 64, 0.5, 0.95);
        result.inside.resize(nb);
        out.readBulk(0, nb * sizeof(Brick), result.inside.data());
    }
    checkGl("winding readback");
    stats.stages.front().gpuMs = uploadTimer.milliseconds();
    if (report) *report = std::move(stats);
    return result;
}

} // namespace svo::gl
