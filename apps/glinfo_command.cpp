// svo glinfo: which GL device and context svo gets, and what it offers.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "svo/core/error.h"
#include "svo/gl/context.h"

namespace svo::app {

void addGlInfoCommand(CLI::App& app)
{
    auto device = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("glinfo", "Create the headless GL context and print what it is");
    cmd->add_option("--device", *device, "EGL device: auto, hardware, software or an index (env SVO_EGL_DEVICE)");
    cmd->callback([device] {
        if (const std::string why = gl::openGlMissing(); !why.empty())
            throw DeviceError("svo glinfo needs OpenGL, which cannot be loaded here: " + why);
        gl::Context context(gl::ContextOptions{*device, false, ""});
        const auto& i = context.info();
        fmt::print("EGL        {}\nvendor     {}\nrenderer   {}\nversion    {}\n", i.eglDevice, i.vendor, i.renderer,
                   i.version);
        fmt::print("GL_NV_conservative_raster  {}\nmax viewport               {}\nmax storage block          {} bytes\n",
                   i.conservativeRasterNV ? "yes" : "no", i.maxViewport, i.maxStorageBlock);
        fmt::print("program binary formats     {}\nprogram cache              {}\ncontext set-up             {:.1f} ms\n",
                   i.programBinaryFormats,
                   !i.programCache.empty()      ? i.programCache
                   : i.programBinaryFormats > 0 ? std::string("off (SVO_PROGRAM_CACHE)")
                                                : std::string("off (the driver offers no binary formats)"),
                   i.setupMs);
    });
}

} // namespace svo::app
