#pragma once
/// @file program_cache.h (internal)
/// Linked program binaries kept on disk between processes
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
#include <optional>
#include <string>

#include "svo/gl/program.h"

namespace svo::gl {

/// The cache folder `option` asks for: a folder; "off" for none; or "" for
/// $SVO_PROGRAM_CACHE when it is set (empty or "off": none), else
/// $XDG_CACHE_HOME/svo/programs, else $HOME/.cache/svo/programs. Returns ""
/// for none (also when "" finds neither XDG_CACHE_HOME nor HOME).
std::string programCacheFolder(const std::string& option);

class ProgramCache {
public:
    /// `folder` "" turns the cache off. `driver` names the GL driver (vendor,
    /// renderer, version): part of every entry's identity.
    ProgramCache(std::string folder, std::string driver);

    bool enabled() const { return !folder_.empty(); }
    const std::string& folder() const { return folder_; }

    enum class Lookup {
        Absent,  ///< no entry (or the cache is off, or the entry cannot be read)
        Loaded,  ///< the program came from its entry
        Refused, ///< an entry exists but is damaged, of another identity, or refused by the driver
    };
    /// The program `source` links to, from its entry, or nothing (`how` says
    /// why). Throws only what Program::fromBinary throws (GL errors).
    std::optional<Program> load(const ProgramSource& source, Lookup& how) const;

    /// Writes the entry of `program`, linked from `source` with its binary
    /// retrievable, atomically (a temporary file, then a rename), replacing
    /// any entry there. Returns a one-line warning the first time the folder
    /// cannot be written or the driver returns no binary (later stores then
    /// do nothing), else "". File errors never throw; GL errors reading the
    /// binary do.
    std::string store(const ProgramSource& source, const Program& program);

    /// Where the entry of `source` lives.
    std::string entryPath(const ProgramSource& source) const;

private:
    std::string identity(const ProgramSource& source) const;
    std::string folder_, driver_;
    bool writable_ = true;
};

} // namespace svo::gl
