#include "svo/gl/timer_query.h"

namespace svo::gl {

TimerQuery::TimerQuery()
{
    GLuint n[2] = {0, 0};
    glCreateQueries(GL_TIMESTAMP, 2, n);
    begin_ = Handle<detail::deleteQuery>(n[0]);
    end_ = Handle<detail::deleteQuery>(n[1]);
}

double TimerQuery::milliseconds() const
{
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(begin_.get(), GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(end_.get(), GL_QUERY_RESULT, &t1);
    return t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0;
}

} // namespace svo::gl
