#include "svo/core/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <random>
#include <unistd.h>

#include "svo/core/error.h"
#include "svo/core/exit_cleanup.h"

namespace svo {
namespace fs = std::filesystem;

void checkWritable(const std::string& path)
{
    if (path.empty()) throw Error("the output path is empty");
    const fs::path p(path);
    std::error_code ec;
    if (fs::is_directory(p, ec)) throw Error(fmt::format("{}: is a folder; give a file name", path));
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: the folder {} does not exist", path, dir.string()));
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(fmt::format("{}: the folder {} is not writable", path, dir.string()));
}

void writeAtomically(const std::string& path, const std::function<void(const std::string& tmp)>& write)
{
    checkWritable(path);
    std::random_device rd;
    const std::string tmp = fmt::format("{}.tmp-{:08x}", path, rd());
    // Registered before it exists, so that an interrupt at any point removes it.
    struct Registration {
        int slot;
        ~Registration() { releaseTemporary(slot); }
    } registration{registerTemporary(tmp.c_str())};
    try {
        write(tmp);
    } catch (const Error&) {
        std::remove(tmp.c_str());
        throw;
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw Error(fmt::format("{}: cannot write the file: {}", path, e.what()));
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw Error(fmt::format("{}: cannot move the finished file into place: {}", path, ec.message()));
    }
}

bool sameFile(const std::string& a, const std::string& b)
{
    if (a.empty() || b.empty()) return false;
    std::error_code ec;
    if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec))
        return std::filesystem::equivalent(a, b, ec);
    return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

void writeFileAtomically(const std::string& path, const std::string& bytes)
{
    writeAtomically(path, [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        out.close();
        if (!out) throw Error(fmt::format("{}: cannot write the file", path));
    });
}

} // namespace svo
