#pragma once
/// @file option_info.h
/// @brief How an option of a library struct is declared once, for every
/// front end: its names and its doc beside the struct, its type and default
/// in the struct itself.
///
/// @details A struct whose fields are options has one function beside it,
/// found by argument-dependent lookup, that shows each field to a visitor with
/// its OptionInfo:
/// @code
///   struct Knobs { double width = 3; Shape shape = Shape::Round; };
///   template <typename Visit>
///   void forEachOption(Knobs& k, Visit&& visit)
///   {
///       visit(OptionInfo{"Knobs::width", "width", "how wide, in voxels"}, CheckedNumber{k.width, checkWidth});
///       visit(OptionInfo{"Knobs::shape", "shape", "the shape of the thing"}, k.shape);
///   }
/// @endcode
/// The command line visits a struct to add a flag per field and bind it there;
/// Python visits it to read keywords into it, and to list keywords, defaults
/// and docs for its docstrings and a test of its type stub. The default shown
/// is the field's value in a default-constructed struct. A field is one of:
/// bool, std::string, an enum with names (svo/core/enum_names.h), or one of
/// the wrappers below, which say how a number (or a two-way choice) is read
/// and checked. A bool that is on by default is turned off on the command
/// line, so its declaration gives that flag ("--no-holes").
#include <cstdint>
#include <string>
#include <string_view>

namespace svo {

/// @brief One option's names and doc.
struct OptionInfo {
    /// How the library's errors name the field: "LevelSetOptions::exteriorBand".
    std::string_view identifier;
    /// Python's keyword; the command line's flag is "--" and the keyword with
    /// '-' for '_' unless `flag` is given.
    std::string_view keyword;
    /// One line for --help, docstrings and stubs. An enum's names and every
    /// default are added by the front end.
    std::string_view doc;
    /// The command line's flag where it differs from the keyword's, with any
    /// short form first ("-r,--resolution").
    std::string_view flag = {};
};

/// @brief A double checked by a library rule as it is read: rule(value, name)
/// throws svo::InvalidInput naming the flag or keyword.
struct CheckedNumber {
    double& value;                            ///< the field
    void (*rule)(double, const std::string&); ///< checkBand, checkVoxelSize, ...
};

/// @brief A whole number checked by a library rule as it is read, kept in the
/// field's own integer type (int, uint32_t): a front end reads a value of type
/// Read, by default the field's, so what that type cannot hold is refused
/// before any rule runs. A wider Read (int64_t for a size_t count) lets the
/// rule, not the parser, refuse a negative number with its own message; the
/// rule must then refuse all that Int cannot hold.
/// rule(value, name) throws svo::InvalidInput naming the flag or keyword.
template <typename Int, typename Read = Int>
struct CheckedInteger {
    Int& value;                                ///< the field
    void (*rule)(int64_t, const std::string&); ///< checkAoConeCount, ...
};

/// @brief A bool given by one of two names rather than as a flag
/// ("isotropic" or "directional"), for a choice that is not on or off.
struct NamedBool {
    bool& value;                 ///< the field
    std::string_view falseName;  ///< the name of false, listed first
    std::string_view trueName;   ///< the name of true
};

/// @brief A number a caller may leave out, checked by a library rule when
/// given: its field's 0 means "not given" (None in Python; no default shown
/// on the command line). T is double or int64_t; the rule sees a double, so
/// that 8.5 given for a whole number is refused by the rule, not truncated.
template <typename T>
struct OptionalNumber {
    T& value;
    void (*rule)(double, const std::string&);
};

/// @brief A number of bytes: "8G", "512M" or a plain number on the command
/// line, an int or None in Python; 0 (the default) means "not given".
struct ByteCount {
    uint64_t& bytes; ///< the field
};

/// @brief A set of AttributeChannel bits, given as names ("normal", ...).
struct ChannelSet {
    uint32_t& bits; ///< the field
};

/// @brief The command line's names of an option, as CLI11 takes them:
/// "--" and its keyword with '-' for '_', or its own ("-r,--resolution").
inline std::string flagNames(const OptionInfo& info)
{
    if (!info.flag.empty()) return std::string(info.flag);
    std::string flag = "--" + std::string(info.keyword);
    for (char& c : flag)
        if (c == '_') c = '-';
    return flag;
}

/// @brief The flag that names an option in messages: its long form ("--resolution").
inline std::string flagOf(const OptionInfo& info)
{
    const std::string names = flagNames(info);
    return names.substr(names.rfind(',') + 1);
}

} // namespace svo
