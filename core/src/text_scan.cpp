#include "text_scan.h"

#include <charconv>
#include <fast_float/fast_float.h>
#include <fmt/format.h>

namespace svo::detail {

bool parseDouble(std::string_view token, double& out)
{
    const char* first = token.data();
    const char* last = first + token.size();
    // fast_float, like std::from_chars, refuses a '+' that text files do write.
    if (first != last && *first == '+' && ++first != last && (*first == '-' || *first == '+')) return false;
    const auto r = fast_float::from_chars(first, last, out);
    return r.ec == std::errc() && r.ptr == last;
}

bool parseInt(std::string_view token, int64_t& out)
{
    const char* first = token.data();
    const char* last = first + token.size();
    if (first != last && *first == '+' && ++first != last && (*first == '-' || *first == '+')) return false;
    const auto r = std::from_chars(first, last, out);
    return r.ec == std::errc() && r.ptr == last && first != last;
}

std::string escaped(std::string_view text)
{
    std::string s;
    s.reserve(text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x20 && c < 0x7f && c != '\\') s += ch;
        else s += fmt::format("\\x{:02X}", c);
    }
    return s;
}

std::string quoted(std::string_view token)
{
    constexpr size_t keep = 40;
    return "'" + escaped(token.substr(0, keep)) + (token.size() > keep ? "...'" : "'");
}

bool equalsNoCase(std::string_view a, std::string_view b)
{
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = char(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

} // namespace svo::detail
