#include "svo/core/voxelization.h"

#include <algorithm>
#include <tbb/parallel_sort.h>

namespace svo {

void sortUniqueKeys(std::vector<uint64_t>& keys)
{
    tbb::parallel_sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

} // namespace svo
