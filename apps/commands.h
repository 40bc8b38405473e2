#pragma once
/// @file commands.h
/// Each subcommand adds itself to the CLI; its callback does the work and
/// throws svo::Error on failure (main turns that into one line and exit 1).
namespace CLI {
class App;
}

namespace svo::app {

void addVoxelizeCommand(CLI::App& app);
void addGlInfoCommand(CLI::App& app);
void addConvertCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);

} // namespace svo::app
