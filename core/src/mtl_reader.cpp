#include "mtl_reader.h"

#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "svo/core/error.h"
#include "text_scan.h"

namespace svo::detail {

std::string_view statementArgument(std::string_view line, std::string_view keyword)
{
    const size_t at = line.find(keyword);
    std::string_view rest = line.substr(at == std::string_view::npos ? line.size() : at + keyword.size());
    while (!rest.empty() && isSpace(rest.front())) rest.remove_prefix(1);
    while (!rest.empty() && isSpace(rest.back())) rest.remove_suffix(1);
    return rest;
}

std::map<std::string, std::optional<Vec3f>> readMtl(const std::string& path, std::string_view bytes)
{
    std::map<std::string, std::optional<Vec3f>> materials;
    std::optional<Vec3f>* current = nullptr;
    size_t lineNo = 0;
    for (size_t start = 0; start < bytes.size();) {
        const size_t nl = bytes.find('\n', start);
        std::string_view line = bytes.substr(start, nl == std::string_view::npos ? std::string_view::npos : nl - start);
        start = nl == std::string_view::npos ? bytes.size() : nl + 1;
        ++lineNo;
        if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        TextScanner words(line);
        const std::string_view keyword = words.next();
        if (keyword == "newmtl") {
            current = &materials[std::string(statementArgument(line, keyword))];
            *current = std::nullopt;
            continue;
        }
        if (keyword != "Kd") continue; // Ka, Ks, Ns, d, illum, map_Kd, ...: not a surface colour svo keeps
        auto fail = [&](const std::string& what) {
            return IoError(fmt::format("{}: line {}: {}", path, lineNo, what));
        };
        if (!current) throw fail("Kd before any newmtl");
        const std::string_view first = words.next();
        if (first == "spectral" || first == "xyz") continue; // no RGB: the material stays without a colour
        double c[3];
        int n = 0;
        for (std::string_view t = first; !t.empty(); t = words.next(), ++n) {
            if (n == 3) throw fail("Kd has more than 3 numbers");
            if (!parseDouble(t, c[n])) throw fail(fmt::format("malformed number {} in Kd", quoted(t)));
            if (!std::isfinite(c[n])) throw fail(fmt::format("non-finite number {} in Kd", quoted(t)));
        }
        if (n == 0) throw fail("Kd without a colour");
        if (n == 2) throw fail("Kd needs 1 or 3 numbers, this one has 2");
        if (n == 1) c[1] = c[2] = c[0]; // one number: grey, as the MTL format defines
        *current = Vec3f{float(c[0]), float(c[1]), float(c[2])};
    }
    return materials;
}

} // namespace svo::detail
