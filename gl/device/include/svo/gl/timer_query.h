#pragma once
/// @file timer_query.h
/// GPU time of an interval, from timestamp queries.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// GPU time between begin() and end(), from a pair of GL_TIMESTAMP queries.
/// (Mesa's llvmpipe returns garbage for GL_TIME_ELAPSED; timestamps measure the
/// same interval on every driver.) The result is read later.
class TimerQuery {
public:
    TimerQuery();
    void begin() const { glQueryCounter(begin_.get(), GL_TIMESTAMP); }
    void end() const { glQueryCounter(end_.get(), GL_TIMESTAMP); }
    /// Waits for the GPU; milliseconds.
    double milliseconds() const;

private:
    Handle<detail::deleteQuery> begin_, end_;
};

} // namespace svo::gl
