// libFuzzer target: the .vdb reader must turn any bytes into bricks that lie
// inside their grid, or into svo::Error; nothing else (no crash, no other
// exception, no out-of-bounds access in svo's code under AddressSanitizer).
// OpenVDB itself is Debian's build, not instrumented: a bad access inside it
// shows only where it crashes or touches memory svo's code or the sanitizer
// runtime checks (memcpy, allocations).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "one_thread.h"
#include "svo/core/error.h"
#include "svo/core/voxel_key.h"
#include "svo/vdb_io/vdb_file.h"

// OpenVDB 10's RootNode::readTopology puts a child into its table only after
// reading it: when the read throws (a damaged Blosc or zip chunk that passes
// svo's size checks but does not decode), the child leaks. svo cannot reach
// it; the message is still an svo::Error.
extern "C" const char* __lsan_default_suppressions() { return "leak:*RootNode*readTopology*\n"; }

// A .vdb with one leaf takes about 10 KB (the 32^3 node's masks alone are
// 8 KB), beyond the 8,192-byte inputs scripts/fuzz.sh allows the other
// targets: this target raises its own limit (a later flag wins).
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv)
{
    static std::vector<char*> args;
    static char maxLen[] = "-max_len=32768";
    args.assign(*argv, *argv + *argc);
    args.push_back(maxLen);
    args.push_back(nullptr);
    *argc = int(args.size()) - 1;
    *argv = args.data();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        // A root tile of 4096^3 voxels is 2^27 bricks (10 GB): past libFuzzer's
        // 2 GB allocation limit, so the harness asks for at most 2^20 (75 MB).
        const svo::vdb::VdbBricks vb = svo::vdb::readVdbBricks(in, "fuzz.vdb", {}, uint64_t(1) << 20);
        for (const auto& [key, brick] : vb.bricks) {
            const auto c = svo::unpackVoxelKey(key);
            for (int a = 0; a < 3; ++a)
                if (c[a] % 8 != 0 || c[a] >= vb.grid.dims[a]) std::abort(); // a brick outside its grid
        }
    } catch (const svo::Error&) {
    }
    return 0;
}
