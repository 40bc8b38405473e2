#pragma once
/// @file empty_framebuffer.h
/// A framebuffer with no attachments.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// A framebuffer with no attachments: rasterization without a colour target.
class EmptyFramebuffer {
public:
    EmptyFramebuffer(int width, int height);
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, h_.get()); }

private:
    Handle<detail::deleteFramebuffer> h_;
};

} // namespace svo::gl
