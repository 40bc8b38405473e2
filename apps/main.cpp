#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <malloc.h>
#include <string>

#include "cli_options.h"
#include "commands.h"
#include "svo/core/error.h"
#include "svo/result_metadata.h"
#include "interrupt_cleanup.h"

int main(int argc, char** argv)
{
#ifdef __GLIBC__
    // Buffers of 1 MiB and more are mapped and given back when freed. glibc
    // otherwise raises the threshold as large buffers are freed, and the
    // load's buffers freed afterwards stay in the heap: 19 MB of the peak of
    // the 1.3 M-triangle icosphere's level set (docs/design.md, "Reading meshes in parallel").
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
    CLI::App app{"svo: voxelize triangle meshes on the GPU (OpenGL 4.5) into sparse voxel octrees and OpenVDB grids"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("svo ") + svo::version()); // the one version (result_metadata.h)
    svo::app::addVoxelizeCommand(app);
    svo::app::addConvertCommand(app);
    svo::app::addInfoCommand(app);
#ifdef SVO_WITH_VALIDATE // CGAL, optional (CMake option SVO_WITH_VALIDATE)
    svo::app::addValidateCommand(app);
#endif
#ifdef SVO_WITH_VTK // VTK, optional (CMake option SVO_WITH_VTK)
    svo::app::addVtkCommand(app);
#endif
    svo::app::addSceneCommand(app);
    svo::app::addViewCommand(app);
    svo::app::addGlInfoCommand(app);
    // Ctrl-C and SIGTERM remove temporary files and stop Xvfb, then exit 130 / 143.
    svo::app::installInterruptCleanup();
    // Usage errors in one line, like every other error.
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return "svo: error: " + svo::app::printable(e.what()) + " (see --help)\n";
    });
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 1; // --help and --version exit 0; bad arguments are errors (1)
    } catch (const svo::app::Failure& e) {
        fmt::print(stderr, "svo: {}\n", svo::app::printable(e.what()));
        return e.code;
    } catch (const svo::Error& e) {
        fmt::print(stderr, "svo: error: {}\n", svo::app::printable(svo::app::errorMessage(e)));
        return 1;
    } catch (const std::exception& e) {
        fmt::print(stderr, "svo: internal error: {}\n", svo::app::printable(e.what()));
        return 2;
    }
    return 0;
}
