#pragma once
/// @file atomic_file.h
/// Output files that appear whole or not at all.
#include <functional>
#include <string>

namespace svo {

/// Fails early, before any heavy work, if `path` cannot be created: its folder
/// is missing or not writable, or it names a folder. Throws svo::Error.
void checkWritable(const std::string& path);

/// Calls `write` with a temporary path in the same folder as `path`, then
/// renames the temporary onto `path`. If `write` throws or the rename fails,
/// the temporary is removed and any earlier file at `path` is left untouched;
/// the error is rethrown as svo::Error naming `path`.
void writeAtomically(const std::string& path, const std::function<void(const std::string& tmp)>& write);

/// True when the two paths name one file: the same device and inode when both
/// exist (so symbolic and hard links count), the same resolved path otherwise
/// (`./`, `..` and linked folders resolved). Empty paths name no file.
bool sameFile(const std::string& a, const std::string& b);

/// writeAtomically for bytes already in memory (text or binary).
void writeFileAtomically(const std::string& path, const std::string& bytes);

} // namespace svo
