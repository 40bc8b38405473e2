#pragma once
/// @file error.h
/// @brief The exceptions svo throws: one base class, svo::Error, and a class
/// for each kind of failure, so that a caller chooses what to do by type and
/// a front end by type and option, never by reading the message.
///
/// @details Every message is a complete sentence a user can act on (it names
/// the file, the option or the value and the problem). Where one option or
/// argument is at fault, the error also keeps its identifier apart from the
/// words: a short, stable name such as "LevelSetOptions::exteriorBand" or
/// "AmbientOcclusion::volumeResolution", which a front end turns into its own
/// name for it (the command line into a flag, @c --exterior-band) with
/// Error::message. The library's rules for numbers (checkBand, checkResolution,
/// ...) take the name to use, so a front end that checks a value itself
/// passes its flag or keyword, and that name becomes the identifier.
///
/// | class        | what failed                                           | Python            |
/// |--------------|-------------------------------------------------------|-------------------|
/// | InvalidInput | a bad mesh, option or argument value, impossible grid | ValueError        |
/// | IoError      | a file cannot be read, is damaged, cannot be written  | OSError           |
/// | DeviceError  | no usable GPU or driver, a GL failure, a GPU limit    | RuntimeError      |
/// | OutOfMemory  | host or GPU memory (or the GPU budget) is exhausted   | MemoryError       |
/// | BufferLimit  | (an OutOfMemory) one GPU buffer cannot hold an array  | MemoryError       |
/// | Unsupported  | a request svo has no method for, found while working  | NotImplementedError |
/// | Interrupted  | the caller's interrupter asked to stop                | KeyboardInterrupt |
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace svo {

/// @brief The base of every exception svo throws for bad input or an unusable
/// environment. The command line prints its message on one line and exits 1.
class Error : public std::runtime_error {
public:
    /// @brief One piece of a message: plain words, or the name of an option
    /// (an identifier, written as the library words it).
    struct Part {
        Part(std::string words) : text(std::move(words)) {}
        Part(const char* words) : text(words) {}
        Part(std::string words, std::string identifier) : text(std::move(words)), option(std::move(identifier)) {}
        std::string text;   ///< as the library's message writes it
        std::string option; ///< the option's identifier; empty for plain words
    };
    /// @brief The name of an option inside a message: @a identifier, written
    /// @a text in the library's message (the identifier itself by default).
    static Part option(std::string identifier, std::string text = {})
    {
        if (text.empty()) text = identifier;
        return Part(std::move(text), std::move(identifier));
    }

    /// @brief An error whose message names no option.
    explicit Error(const std::string& message) : Error(std::vector<Part>{Part(message)}) {}
    /// @brief An error about one option or argument: the message is
    /// "<argument> <detail>", e.g. argument "LevelSetOptions::exteriorBand",
    /// detail "0.5: a band is a number of voxels from 1 to 1000".
    Error(std::string argument, std::string detail)
        : Error(argument.empty() ? std::vector<Part>{Part(std::move(detail))}
                                 : std::vector<Part>{option(std::move(argument)), Part(" " + detail)})
    {
    }
    /// @brief A message that names options anywhere, any number of times:
    /// its parts in order, e.g. {option("VoxelizeOptions::mode"), " thin: ",
    /// option("VoxelizeOptions::mode"), " applies to surface voxels"}.
    explicit Error(std::vector<Part> parts) : Error(makeData(std::move(parts))) {}

    /// @brief The identifier of the option or argument at fault: the first one
    /// the message names; empty when it names none.
    const std::string& argument() const noexcept { return data_->argument; }
    /// @brief The message after its leading argument ("0.5: a band is ..."),
    /// or the whole message when it does not start with one. Options it names
    /// further on are written as the library writes them.
    const std::string& detail() const noexcept { return data_->detail; }
    /// @brief The message with each option it names written as @a name
    /// returns for its identifier (a front end's flag or keyword), or as the
    /// library writes it where @a name returns an empty string. what() is
    /// the message as the library writes it.
    std::string message(const std::function<std::string(const std::string& identifier)>& name) const
    {
        std::string out;
        for (const Part& p : data_->parts) {
            const std::string own = p.option.empty() ? std::string() : name(p.option);
            out += own.empty() ? p.text : own;
        }
        return out;
    }

private:
    struct Data {
        std::vector<Part> parts;
        std::string argument, detail;
    };
    explicit Error(std::shared_ptr<const Data> data) : std::runtime_error(joined(data->parts, 0)), data_(std::move(data))
    {
    }
    static std::string joined(const std::vector<Part>& parts, size_t from)
    {
        std::string out;
        for (size_t i = from; i < parts.size(); ++i) out += parts[i].text;
        return out;
    }
    static std::shared_ptr<const Data> makeData(std::vector<Part> parts)
    {
        Data d;
        for (const Part& p : parts)
            if (!p.option.empty()) {
                d.argument = p.option;
                break;
            }
        const bool leading = !parts.empty() && !parts.front().option.empty();
        d.detail = joined(parts, leading ? 1 : 0);
        if (leading && !d.detail.empty() && d.detail.front() == ' ') d.detail.erase(0, 1);
        d.parts = std::move(parts);
        return std::make_shared<const Data>(std::move(d));
    }

    std::shared_ptr<const Data> data_; ///< shared: copying an exception never throws
};

/// @brief Bad input: a malformed or inconsistent mesh, an option or argument
/// value outside its rule, options that contradict each other, or a grid svo
/// cannot make. The caller can fix it by asking differently.
class InvalidInput : public Error {
public:
    using Error::Error;
};

/// @brief A file that cannot be read, is damaged or not of its format, or
/// cannot be written (the path, its folder, the disk).
class IoError : public Error {
public:
    using Error::Error;
};

/// @brief The machine cannot do the work: no usable GPU or driver, a GL or
/// EGL failure, a limit of the GPU or its driver (buffer sizes, loop limits),
/// or an external library or program that failed (Embree, OpenVDB, Xvfb).
class DeviceError : public Error {
public:
    using Error::Error;
};

/// @brief Memory ran out: host memory, GPU memory, or the GPU memory budget
/// (VoxelizeOptions::gpuMemory) cannot hold the work.
class OutOfMemory : public Error {
public:
    using Error::Error;
};

/// @brief One GPU buffer cannot hold an array of the work, past the bytes a
/// shader addresses (GL_MAX_SHADER_STORAGE_BLOCK_SIZE) though memory may
/// remain: the same work cut into smaller regions fits. An OutOfMemory, so a
/// caller that does not cut its work handles both alike.
class BufferLimit : public OutOfMemory {
public:
    using OutOfMemory::OutOfMemory;
};

/// @brief A well-formed request svo has no method for, found while the work
/// runs: parity signs through a mesh with holes, a level set on the CPU
/// backend or with a non-uniform transform, a grid beyond what one octree,
/// pass or lighting volume of svo holds.
class Unsupported : public Error {
public:
    using Error::Error;
};

/// @brief Thrown when the caller's interrupter asked to stop. Nothing partial
/// is returned and nothing is written; the object that was working stays usable.
class Interrupted : public Error {
public:
    using Error::Error;
};

} // namespace svo
