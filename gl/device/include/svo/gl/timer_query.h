#pragma once
/// @file timer_query.h
/// @brief svo::gl::TimerQuery: GPU time of an interval, from timestamp queries.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// @brief GPU time between begin() and end(), from a pair of GL_TIMESTAMP queries.
/// (Mesa's llvmpipe returns garbage for GL_TIME_ELAPSED; timestamps measure the
/// same interval on every driver.) The result is read later.
class TimerQuery {
public:
    /// @brief Creates the two queries (needs a current Context).
    TimerQuery();
    /// @brief Records the start timestamp after the commands issued so far.
    void begin() const { glQueryCounter(begin_.get(), GL_TIMESTAMP); }
    /// @brief Records the end timestamp after the commands issued so far.
    void end() const { glQueryCounter(end_.get(), GL_TIMESTAMP); }
    /// @brief The GPU time from begin() to end(), waiting for the GPU.
    /// @return milliseconds; 0 when the end is not after the begin
    double milliseconds() const;

private:
    Handle<detail::deleteQuery> begin_, end_;
};

} // namespace svo::gl
