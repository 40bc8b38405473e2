#include "svo/gl/device.h"

#include <cstdlib>
#include <fmt/format.h>
#include <utility>

#include "svo/core/error.h"

namespace svo::gl {

Device::Device(const DeviceOptions& options) : options_(options) {}
Device::~Device() = default;
Device::Device(Device&&) noexcept = default;
Device& Device::operator=(Device&&) noexcept = default;

Context& Device::context()
{
    if (!context_) {
        // A machine without GL stays so: the reason is kept, not paid for again on every call.
        if (!failed_.empty()) throw DeviceError(failed_);
        try {
            context_ = std::make_unique<Context>(
                ContextOptions{options_.device, options_.glDebug, options_.programCache});
        } catch (const DeviceError& e) {
            failed_ = e.what();
            throw;
        }
        unreportedEglMs_ = context_->info().setupMs;
    }
    return *context_;
}

bool Device::named() const
{
    const char* env = std::getenv("SVO_EGL_DEVICE");
    const std::string want = !options_.device.empty() ? options_.device : env && *env ? env : "auto";
    return want != "auto";
}

bool Device::withoutGl(bool create)
{
    if (context_ || named()) return false;
    if (!openGlMissing().empty()) return true;
    if (!create) return !failed_.empty();
    try {
        context();
        return false;
    } catch (const DeviceError&) {
        return true;
    }
}

bool Device::software(bool create)
{
    return context_ || create ? context().info().software : softwareDevice(options_.device);
}

std::string Device::describe()
{
    const auto& i = context().info();
    std::string exts;
    for (const auto& e : i.extensionsUsed) exts += ", " + e;
    return fmt::format("{} | {} | {} ({}{})", i.vendor, i.renderer, i.version, i.eglDevice, exts);
}

StartupStats Device::takeStartup(std::vector<std::string>& warnings)
{
    StartupStats s;
    s.eglMs = std::exchange(unreportedEglMs_, 0.0);
    if (!context_) return s;
    const ProgramStats& now = context_->programStats();
    s.programMs = now.ms - reported_.ms;
    s.programsCompiled = now.compiled - reported_.compiled;
    s.programsLoaded = now.loaded - reported_.loaded;
    s.programsRefused = now.refused - reported_.refused;
    s.programCache = context_->info().programCache;
    warnings.insert(warnings.end(), now.warnings.begin() + std::ptrdiff_t(reported_.warnings.size()),
                    now.warnings.end());
    reported_ = now;
    return s;
}

void Device::releaseScratch()
{
    if (context_) context_->releaseScratch();
    windingTrees_.clear();
}

} // namespace svo::gl
