#pragma once
/// @file view_keys.h
/// svo view's window keys, declared once: the window's key handler presses
/// them through this table, its panel labels and lists them from it, and
/// `svo view --help` prints it (viewKeysHelp).
#include <fmt/format.h>
#include <string>
#include <string_view>
#include <utility>

namespace svo::app {

/// What a key does in the window.
enum class ViewAction {
    Voxels, Outlines, Mesh, Bricks, Color, Lighting, AmbientOcclusion, AoOnly, Finer, Coarser, Backend, Dilation,
    Mode, Frame, AlongX, AlongY, AlongZ, Screenshot, Quit
};

/// One row of the table: the characters that press it (the first is its
/// name in the panel and in --keys scripts), other keys that do the same,
/// and what it does.
struct ViewKey {
    std::string_view chars;
    std::string_view alsoKeys;
    ViewAction action;
    std::string_view does;
};

inline constexpr ViewKey kViewKeys[] = {
    {"v", "", ViewAction::Voxels, "voxels on/off"},
    {"o", "", ViewAction::Outlines, "octree node outlines on/off"},
    {"m", "", ViewAction::Mesh, "the input mesh on/off (mesh inputs)"},
    {"k", "", ViewAction::Bricks, "brick boxes on/off"},
    {"a", "", ViewAction::Color, "next voxel colour: flat, normal, colour, triangle id (voxelizes again with them)"},
    {"l", "", ViewAction::Lighting, "lighting: off, direct, direct + one bounce"},
    {"g", "", ViewAction::AmbientOcclusion, "ambient occlusion on/off"},
    {"r", "", ViewAction::AoOnly, "ambient occlusion alone on/off"},
    {"+=", "keypad +", ViewAction::Finer, "voxelize again at twice the resolution (mesh inputs)"},
    {"-", "keypad -", ViewAction::Coarser, "voxelize again at half the resolution (mesh inputs)"},
    {"b", "", ViewAction::Backend, "next backend (--backend), voxelize again"},
    {"c", "", ViewAction::Dilation, "next dilation (--dilation), voxelize again"},
    {"t", "", ViewAction::Mode, "next mode (--mode), voxelize again"},
    {"f", "", ViewAction::Frame, "frame everything, looking the same way"},
    {"x", "", ViewAction::AlongX, "orthographic view along x"},
    {"y", "", ViewAction::AlongY, "orthographic view along y"},
    {"z", "", ViewAction::AlongZ, "orthographic view along z"},
    {"p", "", ViewAction::Screenshot, "screenshot to svo-view-N.png in the current folder"},
    {"q", "Esc", ViewAction::Quit, "close the window"},
};

/// The mouse, for the same lists (not keys: the window's cursor callbacks).
inline constexpr std::pair<std::string_view, std::string_view> kViewMouse[] = {
    {"left drag", "orbit around the target"},
    {"right or middle drag", "pan"},
    {"wheel", "zoom"},
};

/// The row a character presses, or nullptr (letters in either case).
inline const ViewKey* viewKeyOf(char c)
{
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    for (const ViewKey& k : kViewKeys)
        if (k.chars.find(c) != std::string_view::npos) return &k;
    return nullptr;
}

/// The row of an action (every action has one).
inline const ViewKey& viewKeyFor(ViewAction a)
{
    for (const ViewKey& k : kViewKeys)
        if (k.action == a) return k;
    return kViewKeys[0];
}

/// "name (K)": a panel label with the action's first key, upper-case.
inline std::string viewKeyLabel(std::string_view name, ViewAction a)
{
    const char c = viewKeyFor(a).chars[0];
    return fmt::format("{} ({})", name, c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c);
}

/// A row's keys as lists write them: "+ =, keypad +".
inline std::string viewKeyNames(const ViewKey& k)
{
    std::string out;
    for (char c : k.chars) out += fmt::format("{}{}", out.empty() ? "" : " ", c);
    if (!k.alsoKeys.empty()) out += fmt::format(", {}", k.alsoKeys);
    return out;
}

/// The keys and the mouse as `svo view --help` lists them.
inline std::string viewKeysHelp()
{
    std::string out = "Window keys (--keys presses them too, one a frame):\n";
    for (const ViewKey& k : kViewKeys) out += fmt::format("  {:<22} {}\n", viewKeyNames(k), k.does);
    out += "Window mouse:\n";
    for (const auto& [what, does] : kViewMouse) out += fmt::format("  {:<22} {}\n", what, does);
    return out;
}

} // namespace svo::app
