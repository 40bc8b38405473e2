#pragma once
/// @file fill_words.h
/// @brief svo::gl::fillWords: a large buffer set to one 32-bit value by a
/// compute shader, in place of glClearNamedBufferSubData.
///
/// Why: on NVIDIA's driver a clear of memory that nothing has written yet
/// runs far slower than a shader's writes to it (docs/design.md, "Fresh
/// memory and readbacks"), and a fresh process's buffers are all such memory.
#include <cstdint>

namespace svo::gl {

class Buffer;
class Context;

/// @brief Sets the first @a bytes of @a buffer to @a value as 32-bit words,
/// with @a context current, in ranges of at most 1 GiB and the driver's
/// storage block limit (Context::shaderBufferLimit). Shader storage binding 0 is used and restored;
/// the writes are visible to later shader, buffer-update and client reads.
/// @param context the buffer's context
/// @param buffer  the buffer, at least @a bytes long
/// @param value   the word written
/// @param bytes   how many bytes, a multiple of 4; nothing for 0
/// @throw svo::InvalidInput when @a bytes is not a multiple of 4 or exceeds the buffer
void fillWords(const Context& context, const Buffer& buffer, uint32_t value, uint64_t bytes);

} // namespace svo::gl
