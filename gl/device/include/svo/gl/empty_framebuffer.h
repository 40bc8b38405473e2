#pragma once
/// @file empty_framebuffer.h
/// @brief svo::gl::EmptyFramebuffer: a framebuffer with no attachments.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// @brief A framebuffer with no attachments: rasterization without a colour target.
class EmptyFramebuffer {
public:
    /// @brief A framebuffer of default size @a width by @a height, one sample.
    /// @throw svo::DeviceError when the driver finds it incomplete (a size
    ///        past its limits)
    EmptyFramebuffer(int width, int height);
    /// @brief Binds it as GL_FRAMEBUFFER.
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, h_.get()); }

private:
    Handle<detail::deleteFramebuffer> h_;
};

} // namespace svo::gl
