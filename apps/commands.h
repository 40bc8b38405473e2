#pragma once
/// @file commands.h
/// Each subcommand adds itself to the CLI; its callback does the work and
/// throws svo::Error on failure (main turns that into one line and exit 1).
#include <stdexcept>
#include <string>

namespace CLI {
class App;
}

namespace svo::app {

void addVoxelizeCommand(CLI::App& app);
void addGlInfoCommand(CLI::App& app);
void addConvertCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addValidateCommand(CLI::App& app);
void addVtkCommand(CLI::App& app);
void addSceneCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

/// A command that ran to the end but whose verdict is negative (e.g. a
/// validation that found missed voxels): main prints the one-line reason and
/// exits with `code` (3), apart from errors (1).
struct Failure : std::runtime_error {
    Failure(const std::string& reason, int exitCode = 3) : std::runtime_error(reason), code(exitCode) {}
    int code;
};

} // namespace svo::app
