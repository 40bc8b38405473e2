#include "svo/validate/worst_cases.h"

#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo::validate {

void checkWorst(int64_t worst, const std::string& name)
{
    if (worst < 0 || worst > 1000000)
        throw InvalidInput(name, fmt::format("{}: the worst cases listed of each kind are 0 to 1000000", worst));
}

} // namespace svo::validate
