#pragma once
/// @file program_cache.h
/// @brief svo::gl::ProgramCache: linked program binaries kept on disk between processes
/// (glGetProgramBinary / glProgramBinary), so that a new context loads its
/// programs instead of compiling them: compilation is most of a cold start
/// on a small mesh.
///
/// One file per program, named by a 64-bit FNV-1a hash of its identity: the
/// GL vendor, renderer and version strings, then each stage's file name and
/// its text as the driver receives it (includes expanded, #line directives
/// and all; svo passes no other defines). The file repeats the identity in
/// full, so a hash collision reads as a miss, never as a wrong program, and a
/// checksum covers the whole file.
///
/// Nothing here fails a call. An entry that is missing, damaged, of another
/// identity or refused by the driver means compiling, and the entry is
/// written anew; a folder that cannot be written gives one warning, after
/// which the cache only reads.
///
/// Internal to the device layer (Context keeps one); not installed. Callers
/// choose the folder through ContextOptions::programCache.
#include <optional>
#include <string>

#include "svo/gl/program.h"

namespace svo::gl {

/// @brief The cache folder an option asks for. Throws nothing.
/// @param option a folder; "off" for none; or "" for $SVO_PROGRAM_CACHE when
///        it is set (empty or "off": none), else $XDG_CACHE_HOME/svo/programs,
///        else $HOME/.cache/svo/programs
/// @return the folder; "" for none (also when "" finds neither
///         XDG_CACHE_HOME nor HOME)
std::string programCacheFolder(const std::string& option);

/// @brief The program binaries of one GL driver in one folder.
class ProgramCache {
public:
    /// @brief A cache over @a folder; touches no file yet.
    /// @param folder programCacheFolder()'s answer; "" turns the cache off
    /// @param driver names the GL driver (vendor, renderer, version): part of
    ///        every entry's identity
    ProgramCache(std::string folder, std::string driver);

    /// @brief Whether the cache has a folder.
    bool enabled() const { return !folder_.empty(); }
    /// @brief The cache folder; "" when off.
    const std::string& folder() const { return folder_; }

    /// @brief What load() found.
    enum class Lookup {
        Absent,  ///< no entry (or the cache is off, or the entry cannot be read)
        Loaded,  ///< the program came from its entry
        Refused, ///< an entry exists but is damaged, of another identity, or refused by the driver
    };
    /// @brief The program @a source links to, from its entry.
    /// @param how receives what was found
    /// @return the program, or nothing (@a how says why)
    /// @throw svo::OutOfMemory or svo::DeviceError for GL errors
    ///        (Program::fromBinary); file errors never throw
    std::optional<Program> load(const ProgramSource& source, Lookup& how) const;

    /// @brief Writes the entry of @a program, linked from @a source with its
    /// binary retrievable, atomically (a temporary file, then a rename),
    /// replacing any entry there. Nothing when the cache is off.
    /// @return a one-line warning the first time the folder cannot be written
    ///         or the driver returns no binary (later stores then do nothing),
    ///         else ""
    /// @throw svo::OutOfMemory or svo::DeviceError for GL errors reading the
    ///        binary (Program::binary); file errors never throw
    std::string store(const ProgramSource& source, const Program& program);

    /// @brief The path of the entry of @a source.
    std::string entryPath(const ProgramSource& source) const;

private:
    std::string identity(const ProgramSource& source) const;
    std::string folder_, driver_;
    bool writable_ = true;
};

} // namespace svo::gl
