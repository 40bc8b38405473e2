// Loads libsvo_vtk.so, the VTK export module, for `svo vtk` (see vtk_export.h).
#include <dlfcn.h>
#include <filesystem>
#include <fmt/format.h>
#include <string>
#include <system_error>

#include "svo/core/error.h"
#include "vtk_export.h"

#define SVO_STRINGIFY_(x) #x
#define SVO_STRINGIFY(x) SVO_STRINGIFY_(x)

namespace svo::app {
namespace {

/// The module's path: SVO_VTK_MODULE_FROM_BIN (relative, set by CMake to the
/// same layout in the build tree and the install tree) from the executable's folder.
std::filesystem::path modulePath()
{
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw IoError(fmt::format("svo vtk: cannot find svo's own path to load its VTK module: {}", ec.message()));
    return (exe.parent_path() / SVO_VTK_MODULE_FROM_BIN / "libsvo_vtk.so").lexically_normal();
}

const VtkExport& load()
{
    const std::filesystem::path path = modulePath();
    // Kept loaded for the process: VTK does not support being unloaded.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* error = dlerror();
        std::string why = error ? error : "unknown reason";
        const std::string prefix = path.string() + ": ";
        if (why.rfind(prefix, 0) == 0) why.erase(0, prefix.size()); // the loader names the path too
        throw IoError(fmt::format("{}: cannot load svo's VTK module: {}", path.string(), why));
    }
    using Entry = const VtkExport* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, SVO_STRINGIFY(SVO_VTK_MODULE_ENTRY)));
    if (!entry)
        throw IoError(fmt::format("{}: not svo's VTK module of this version (no {})", path.string(),
                                  SVO_STRINGIFY(SVO_VTK_MODULE_ENTRY)));
    return *entry();
}

} // namespace

const VtkExport& vtkExport()
{
    static const VtkExport& functions = load(); // a throw leaves it unset, so a later call retries
    return functions;
}

} // namespace svo::app
