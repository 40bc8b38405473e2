#include "svo/gl/buffer.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "svo/core/error.h"

namespace svo::gl {
namespace {

/// SVO_GL_MAX_BUFFER (bytes): buffers larger fail as GL_OUT_OF_MEMORY would.
/// Drivers refuse allocations that the memory they report promised; this lets
/// tests take that path on any driver (docs/design.md, "GPU memory").
uint64_t maxBufferForTesting()
{
    const char* v = std::getenv("SVO_GL_MAX_BUFFER"); // read each time: tests set it around one call
    return v ? std::strtoull(v, nullptr, 10) : 0;
}

/// memcpy on all cores for large reads: the destination is often fresh host
/// memory, whose page faults dominate a single thread's copy (an H200 read
/// 702 MB back at 1.6 GB/s that way).
void copyOut(unsigned char* dst, const unsigned char* src, uint64_t n)
{
    const uint64_t grain = uint64_t(1) << 20;
    if (n < 8 * grain) {
        std::memcpy(dst, src, n);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, n, grain), [&](const tbb::blocked_range<uint64_t>& r) {
        std::memcpy(dst + r.begin(), src + r.begin(), r.size());
    });
}

} // namespace

Buffer::Buffer(const char* what, uint64_t bytes, const void* data, GLbitfield flags) : bytes_(bytes)
{
    // An error left by earlier work is reported as that work's, not dropped.
    checkGl(fmt::format("the GL work before allocating the {}", what).c_str());
    GLuint n = 0;
    glCreateBuffers(1, &n);
    h_ = Handle<detail::deleteBuffer>(n);
    glNamedBufferStorage(n, GLsizeiptr(bytes ? bytes : 4), data, flags);
    GLenum err = glGetError();
    if (const uint64_t limit = maxBufferForTesting(); limit && bytes > limit && err == GL_NO_ERROR) err = GL_OUT_OF_MEMORY;
    if (err == GL_OUT_OF_MEMORY)
        throw OutOfMemory(fmt::format("the GPU cannot allocate {:.1f} MiB for the {}", double(bytes) / (1 << 20), what));
    if (err != GL_NO_ERROR) throw DeviceError(fmt::format("OpenGL error 0x{:04x} allocating the {}", err, what));
}

void Buffer::read(uint64_t offset, uint64_t bytes, void* out) const
{
    // NVIDIA's driver reads directly by copying the whole buffer: a few
    // bytes of a 747 MB grid took 0.5 s, of a 45 MB scratch buffer 3.2 ms
    // (bench/results/nvidia-h100/nanovdb/band-2026-12-05/passes); through
    // staging, well under a millisecond. Small buffers are read directly.
    constexpr uint64_t kDirectReadLimit = uint64_t(1) << 20;
    if (bytes_ > kDirectReadLimit) return readBulk(offset, bytes, out);
    glGetNamedBufferSubData(h_.get(), GLintptr(offset), GLsizeiptr(bytes), out);
}

void Buffer::readBulk(uint64_t offset, uint64_t bytes, void* out) const
{
    if (!bytes) return;
    const uint64_t chunk = std::min<uint64_t>(bytes, uint64_t(64) << 20);
    const Buffer staging("readback staging buffer", chunk, nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
    auto* dst = static_cast<unsigned char*>(out);
    for (uint64_t done = 0; done < bytes; done += chunk) {
        const uint64_t n = std::min(chunk, bytes - done);
        glCopyNamedBufferSubData(h_.get(), staging.h_.get(), GLintptr(offset + done), 0, GLsizeiptr(n));
        const void* src = glMapNamedBufferRange(staging.h_.get(), 0, GLsizeiptr(n), GL_MAP_READ_BIT);
        if (!src) throw DeviceError(fmt::format("cannot map the readback staging buffer ({} bytes)", n));
        copyOut(dst + done, static_cast<const unsigned char*>(src), n);
        glUnmapNamedBuffer(staging.h_.get());
    }
}

} // namespace svo::gl
