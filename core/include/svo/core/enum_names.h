#pragma once
/// @file enum_names.h
/// @brief An enum's names, written once next to the enum, and what every
/// front end does with them: the name of a value (nameOf), the value of a
/// name (parse, which throws svo::InvalidInput naming the option), and the
/// names in order (names, for help text and the command line's checks).
///
/// @details An enum takes part by a table and one function beside it, in its
/// own namespace (found by argument-dependent lookup):
/// @code
///   enum class Shape { Round, Square };
///   inline constexpr EnumName<Shape> kShapeNames[] = {{Shape::Round, "round"}, {Shape::Square, "square"}};
///   constexpr const auto& enumNames(Shape) { return kShapeNames; }
/// @endcode
#include <string>
#include <string_view>
#include <vector>

#include "svo/core/error.h"

namespace svo {

/// @brief One value of an enum and its name.
template <typename E>
struct EnumName {
    E value;               ///< the value
    std::string_view name; ///< its name, as front ends write it
};

/// @brief The name of @a value; empty for a value the table lacks.
template <typename E>
std::string_view nameOf(E value)
{
    for (const EnumName<E>& n : enumNames(E{}))
        if (n.value == value) return n.name;
    return {};
}

/// @brief The names of E, in the table's order.
template <typename E>
std::vector<std::string> names()
{
    std::vector<std::string> out;
    for (const EnumName<E>& n : enumNames(E{})) out.emplace_back(n.name);
    return out;
}

/// @brief The names of E quoted and joined: "'a', 'b' or 'c'".
template <typename E>
std::string quotedNames()
{
    const std::vector<std::string> all = names<E>();
    std::string out;
    for (size_t i = 0; i < all.size(); ++i)
        out += (i == 0 ? "" : i + 1 == all.size() ? " or " : ", ") + ("'" + all[i] + "'");
    return out;
}

/// @brief The value named @a text.
/// @param identifier the option, flag or keyword that gave the text
/// @throw svo::InvalidInput whose argument() is @a identifier for a name the
///        table lacks: "<identifier>: expected 'a', 'b' or 'c', got 'x'"
template <typename E>
E parse(std::string_view text, const std::string& identifier)
{
    for (const EnumName<E>& n : enumNames(E{}))
        if (n.name == text) return n.value;
    throw InvalidInput(std::vector<Error::Part>{Error::option(identifier),
                                                ": expected " + quotedNames<E>() + ", got '" + std::string(text) + "'"});
}

} // namespace svo
